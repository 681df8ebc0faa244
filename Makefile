# The two commands of the course: `make lab` (a student's install: the course and JupyterLab) and
# `make test` (a developer's: every extra). Both create .venv when it is missing and install
# afmsmiler (editable); the full install satisfies `make lab` too.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.afmsmiler-installed
STUDENT_STAMP := $(VENV)/.afmsmiler-student-installed
export MPLBACKEND ?= Agg

.PHONY: install lab test unit notebooks bench book clean browser firmware

## Debian's Chromium for the browser tests (tests/test_panels_browser.py): installed with apt-get when
## missing and we are root (as in CI); otherwise those tests are skipped and say why.
BROWSER ?= /usr/bin/chromium
browser:
	@test -x $(BROWSER) || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing Debian's chromium for the browser tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null \
	      || echo "apt-get could not install chromium: the browser tests will be skipped"; \
	  else echo "no $(BROWSER) and not root: the browser tests will be skipped"; fi; }

## avr-gcc, the Arduino core and simavr for the firmware tests (tests/test_hardware_firmware*.py):
## the macroscopic AFM's real firmware is built and run in an emulated ATmega2560. Installed with
## apt-get when missing and we are root (as in CI); otherwise those tests are skipped and say why.
FIRMWARE_PACKAGES := gcc-avr avr-libc arduino-core-avr simavr libsimavr-dev
firmware:
	@{ command -v avr-gcc >/dev/null && test -d /usr/share/arduino/hardware/arduino/avr \
	    && test -f /usr/include/simavr/sim_avr.h; } || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing avr-gcc, the Arduino core and simavr for the firmware tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
	      $(FIRMWARE_PACKAGES) >/dev/null \
	      || echo "apt-get could not install them: the firmware tests will be skipped"; \
	  else echo "no avr-gcc/simavr and not root: the firmware tests will be skipped"; fi; }

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,lab,files,bench,hardware]'
	touch $(STAMP) $(STUDENT_STAMP)

## A student's install: the course, JupyterLab and the file readers (no test, bench or hardware
## extras); a full install already has them.
$(STUDENT_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[lab,files]'
	touch $(STUDENT_STAMP)

install: $(STAMP)

## Open the course notebooks in JupyterLab, served on 127.0.0.1 only.
lab: $(STUDENT_STAMP)
	MPLBACKEND= $(VENV)/bin/jupyter lab --ServerApp.ip=127.0.0.1 --ServerApp.root_dir=notebooks \
	  $(if $(DISPLAY),,--no-browser) $(if $(filter 0,$(shell id -u)),--allow-root) $(LAB_ARGS)

## Everything: every test (slow and browser ones too), the docstrings' examples, every notebook
## under nbval. The tests that need no browser run on both cores (pytest-xdist); the browser
## tests, which time key presses to pixels, run alone after them.
test: $(STAMP) browser firmware
	$(PY) -m pytest -n 2 -m "not browser" tests
	$(PY) -m pytest -m browser tests
	$(PY) -m pytest -p no:cacheprovider --doctest-modules afmsmiler
	AFMSMILER_TESTING=1 $(PY) -m pytest --nbval-lax --nbval-current-env -p no:cacheprovider notebooks

## The fast suite while you work: every test except those marked `slow` (a second or more each:
## reference solutions, many fits, code generation, the deep bad-input campaign) and `browser`
## (headless Chromium against JupyterLab and voila).
## No doctests, notebooks or server check: `make test` runs those.
unit: $(STAMP)
	$(PY) -m pytest -m "not slow and not browser" tests

notebooks: $(STAMP)
	AFMSMILER_TESTING=1 $(PY) -m pytest --nbval-lax --nbval-current-env notebooks

## Speed figures, as ratios against each issue's named peer, measured in one run.
bench: $(STAMP) browser
	$(PY) benchmarks/run_all.py

## The course book (Jupyter Book 1.x) into book/_build/html.
book: $(STAMP)
	$(PY) -m pip install --quiet -e '.[book]'
	$(PY) -m afmsmiler.ui.pages book/_static/panels
	$(VENV)/bin/jupyter-book build book

clean:
	rm -rf $(VENV) .pytest_cache book/_build
