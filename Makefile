# The two commands of the course: `make lab` (a student's install: the course and JupyterLab) and
# `make test` (a developer's: every extra). Both create .venv when it is missing and install
# afmsmiler (editable); the full install satisfies `make lab` too.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.afmsmiler-installed
STUDENT_STAMP := $(VENV)/.afmsmiler-student-installed
## pytest-xdist workers (0: one process, as pytest alone). `make test` runs three on two cores: the
## browser tests' two groups (tests/conftest.py:BROWSER_GROUPS) wait for their pages most of the
## time, and the third worker's models fill it (a fourth made it slower here, and starved notebook
## 08's real-time haptic loop until its watchdog fired). `make unit`, all models, runs one a core.
JOBS      ?= 3
UNIT_JOBS ?= 2
export MPLBACKEND ?= Agg
## Python keeps its compiled modules (and pytest its rewritten test modules) in __pycache__:
## where the environment says not to (PYTHONDONTWRITEBYTECODE), every process, each notebook's
## kernel and each test worker, compiled the course and the tests again (10 s per worker).
unexport PYTHONDONTWRITEBYTECODE

.PHONY: install lab test unit lint notebooks bench book clean browser firmware system-packages \
        test-setup assignments app apps hub-proxy lock

## Debian's packages the tests need, installed with apt-get when missing and we are root (as in
## CI); otherwise the tests that need them are skipped and say why. `browser`: Chromium for the
## browser tests (tests/test_panels_browser.py and the others marked `browser`). `firmware`:
## avr-gcc, the Arduino core and simavr for the firmware tests (tests/test_hardware_firmware*.py:
## the macroscopic AFM's real firmware built and run in an emulated ATmega2560). `system-packages`
## (what `make test` runs): both, in one apt-get run (one package-list update, 30 s on a new machine).
BROWSER ?= /usr/bin/chromium
FIRMWARE_PACKAGES := gcc-avr avr-libc arduino-core-avr simavr libsimavr-dev
have-browser  := test -x $(BROWSER)
have-firmware := command -v avr-gcc >/dev/null && test -d /usr/share/arduino/hardware/arduino/avr \
                 && test -f /usr/include/simavr/sim_avr.h
## $(call apt-install,PACKAGES,WHAT): PACKAGES (a shell word list) with apt-get, or say WHAT is skipped
apt-install = if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing$(1) for $(2)"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(1) >/dev/null \
	      || echo "apt-get could not install them: $(2) will be skipped"; \
	  else echo "missing$(1) and not root: $(2) will be skipped"; fi
browser:
	@$(have-browser) || { $(call apt-install, chromium,the browser tests); }
firmware:
	@{ $(have-firmware); } || { $(call apt-install, $(FIRMWARE_PACKAGES),the firmware tests); }
system-packages:
	@missing=""; what=""; \
	$(have-browser) || { missing=" chromium"; what="the browser tests"; }; \
	{ $(have-firmware); } || { missing="$$missing $(FIRMWARE_PACKAGES)"; \
	  what="$${what:+$$what and }the firmware tests"; }; \
	test -z "$$missing" || { $(call apt-install,$$missing,$$what); }

## uv (from PyPI) installs in parallel: about 35 s for every extra where pip took about 2 min;
## pip does it when uv cannot. (uv's --compile-bytecode, all 220 packages compiled at install, cost
## make test more than the first imports it saves: each is compiled once, on first use.)
## The versions are those of the lock binder/requirements.txt (constraints: what the tests passed
## with, what a class's image installs; `make lock` writes it again after an upgrade).
EXTRAS := test,lab,files,bench,hardware,book,hub
LOCK   := binder/requirements.txt
$(STAMP): pyproject.toml $(LOCK)
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	{ $(PY) -m pip install --quiet uv && \
	  $(VENV)/bin/uv pip install --quiet --python $(PY) -e '.[$(EXTRAS)]' -c $(LOCK); } || \
	  { $(PY) -m pip install --quiet --upgrade pip && \
	    $(PY) -m pip install --quiet -e '.[$(EXTRAS)]' -c $(LOCK); }
	$(MAKE) --no-print-directory nbgrader-extensions-off
	touch $(STAMP) $(STUDENT_STAMP)

## nbgrader (in the test extra: tests/test_grade_run.py) is used through its command line and
## Python API only. Its server and JupyterLab extensions would load into every Jupyter server of
## .venv (JupyterLab, voila, a hub's servers: 1.5 s more at each start, its imports' memory, its
## menus in the browser tests' pages), so a developer's install turns them off. The tool writes
## what `jupyter server/labextension disable --sys-prefix` write, through the same functions,
## in 0.1 s (the five commands took 21 s of every fresh install).
.PHONY: nbgrader-extensions-off
nbgrader-extensions-off:
	$(PY) tools/nbgrader_extensions_off.py

## A student's install: the course with its notebooks' UI (lab), the file readers (files) and
## the devices (hardware); no test or bench extras. A full install already has them.
$(STUDENT_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[lab,files,hardware]'
	touch $(STUDENT_STAMP)

install: $(STAMP)

## Open the course notebooks in JupyterLab, served on 127.0.0.1 only.
lab: $(STUDENT_STAMP)
	MPLBACKEND= $(VENV)/bin/jupyter lab --ServerApp.ip=127.0.0.1 --ServerApp.root_dir=notebooks \
	  --ServerApp.kernel_websocket_connection_class=afmsmiler.serving.NoDelayConnection \
	  $(if $(DISPLAY),,--no-browser) $(if $(filter 0,$(shell id -u)),--allow-root) $(LAB_ARGS)

## A module as a web app (voila, 127.0.0.1 only: code hidden, widgets and 3D views live):
## `make app NB=06_virtual_imaging`; `make apps` serves the index of every module. The app is the
## notebook itself, run and rendered by voila (afmsmiler/apps.py).
NB ?= 01_cantilever_mechanics
app: $(STUDENT_STAMP)
	$(PY) -m afmsmiler.apps $(NB) $(if $(DISPLAY),--browser)
apps: $(STUDENT_STAMP)
	$(PY) -m afmsmiler.apps $(if $(DISPLAY),--browser)

## JupyterHub's proxy (configurable-http-proxy, from the npm registry) into .hub/, for the local
## hub of tests/test_hub_browser.py and benchmarks/bench_hub.py; skipped without npm.
CHP_VERSION := 5.3.0
hub-proxy:
	@test -x .hub/node_modules/.bin/configurable-http-proxy || { \
	  if command -v npm >/dev/null; then \
	    npm install --silent --no-audit --no-fund --prefix .hub configurable-http-proxy@$(CHP_VERSION); \
	  else echo "no npm: the hub test will be skipped"; fi; }

## binder/requirements.txt: the exact versions installed in .venv (what `make test` passed with),
## for repo2docker (Binder, a JupyterHub's image). Run it after an upgrade. The installers
## themselves (pip, setuptools, wheel, uv: the venv's and PyPI's own) are not pinned.
lock:
	$(VENV)/bin/uv pip freeze --quiet --python $(PY) --exclude-editable \
	  | grep -v -E '^(pip|setuptools|wheel|uv)==' > $(LOCK).new
	mv $(LOCK).new $(LOCK)

## What `make test` needs, installed side by side (Python packages from PyPI, Debian's packages,
## the hub's proxy from npm: each mostly waits on its downloads): `make -j3` of the three.
test-setup:
	@$(MAKE) --no-print-directory -j3 $(STAMP) system-packages hub-proxy

## Everything: the linter, then one pytest run of every test (slow and browser ones too), the
## docstrings' examples and every notebook under nbval, on $(JOBS) pytest-xdist workers, the
## longest first (tests/conftest.py). The browser tests are two xdist groups (their modules share
## servers and Chromium), one worker each; each notebook is a group too (its cells in order, in one
## kernel, on one worker). One run, not three: the notebooks and doctests fill the cores while
## the browser tests wait for their pages (36 s less than three runs one after the other here).
## AFMSMILER_TESTING=1 shortens the notebooks' animations (as CI=true does). Tests check
## correctness, not speed (`make bench` does).
test: test-setup lint
	AFMSMILER_TESTING=1 $(PY) -m pytest --nbval-lax --nbval-current-env --doctest-modules \
	  -n $(JOBS) --dist loadgroup --durations=40 tests afmsmiler notebooks

## The fast suite while you work, on both cores: every test except those marked `slow` (a second
## or more each: reference solutions, many fits, code generation, the deep bad-input campaign) and
## `browser` (headless Chromium against JupyterLab and voila).
## No linter, doctests, notebooks or server check: `make test` runs those. (`-p no:nbval`: nbval's
## plugin imports nbformat and jsonschema, 2.5 s of CPU in each process, for the notebooks only.)
unit: $(STAMP)
	$(PY) -m pytest -p no:nbval -n $(UNIT_JOBS) -m "not slow and not browser" tests

## ruff, with the rules in pyproject.toml ([tool.ruff]); `make test` runs it first.
lint: $(STAMP)
	$(VENV)/bin/ruff check afmsmiler tests benchmarks tools

notebooks: $(STAMP)
	AFMSMILER_TESTING=1 $(PY) -m pytest --nbval-lax --nbval-current-env -n $(JOBS) --dist loadfile \
	  notebooks

## Speed figures, as ratios against each issue's named peer, measured in one run.
bench: $(STAMP) browser hub-proxy
	$(PY) benchmarks/run_all.py

## An instructor's nbgrader assignments, one per notebook (the course and nbgrader, the `course`
## extra, on top of a student's install): the source versions (solutions and
## autograder tests made from afmsmiler.exercises: python -m afmsmiler.grade --help) in
## $(COURSE)/source/ and the students' versions in $(COURSE)/release/ (nbgrader generate_assignment).
## Autograde in $(COURSE) with nbgrader as usual: its nbgrader_config.py (written when missing) runs
## the notebooks as the grade command does (AFMSMILER_TESTING=1, up to 600 s per cell).
COURSE ?= course
assignments: $(STUDENT_STAMP)
	$(PY) -m pip install --quiet -e '.[course]'
	$(PY) -m afmsmiler.grade --nbgrader-source $(COURSE)/source notebooks/0*.ipynb
	test -f $(COURSE)/nbgrader_config.py || printf '%s\n' \
	  '# nbgrader runs the notebooks as python -m afmsmiler.grade does: short animations, and' \
	  '# room for the longest cells (module (h) scans its simulated devices)' \
	  'import os' 'os.environ.setdefault("AFMSMILER_TESTING", "1")' \
	  'os.environ.setdefault("MPLBACKEND", "Agg")' 'c = get_config()  # noqa: F821' \
	  'c.Execute.timeout = 600' > $(COURSE)/nbgrader_config.py
	cd $(COURSE) && for a in source/*/; do \
	  PATH="$(abspath $(VENV))/bin:$$PATH" nbgrader generate_assignment --force "$$(basename $$a)" \
	    || exit 1; done

## The course book (Jupyter Book 1.x) into book/_build/html, warnings as errors. Its figure and
## 3D pages are written from the panels' registry; MathJax ships in the build (the pinned npm
## release, hash-checked, fetched once into book/_vendor or read from MATHJAX_TARBALL), so
## the build and its pages need no network (tests/test_book_browser.py checks both).
MATHJAX := book/_extra/mathjax/tex-mml-chtml.js
$(MATHJAX): tools/vendor_mathjax.py
	$(PY) tools/vendor_mathjax.py book/_extra/mathjax
book: $(STAMP) $(MATHJAX)
	$(PY) -m afmsmiler.ui.pages book/_static/panels
	$(VENV)/bin/jupyter-book build -W -n --keep-going book

clean:
	rm -rf $(VENV) .pytest_cache book/_build book/_static/panels book/_extra
