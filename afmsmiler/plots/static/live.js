// The browser side of afmsmiler's live figures (afmsmiler/plots/live.py).
//
// The kernel describes a figure as a layout (axes on a grid, series styles, labels: what rarely
// changes), a frame (limits, titles, texts, reference lines, legends: small) and one binary buffer
// of float32 holding every curve and image of the frame. A new layout rebuilds the uPlot charts;
// a new frame only swaps data and limits. uPlot (the kept library, shipped beside this file) draws
// axes and curves; images, spans, reference lines and texts are drawn in its hooks.
//
// Every frame the kernel sends is drawn once and painted once (Figure.push): frames are drawn only
// in animation-frame callbacks, one per animation frame, so no draw is overwritten before the
// browser painted it. The kernel coalesces a drag's moves (afmsmiler/ui/panel.py), so frames come
// no faster than the model runs. The root element counts the frames drawn (data-frames), names the
// kernel's sequence number drawn last (data-seq), and counts the frames known painted
// (data-painted; their sequence numbers in Figure.paintedSeqs), which the browser tests and the
// benchmark read.
//
// This file holds no physics: every number comes from the kernel.

const PX = 100 / 72; // px per point at the figure's 100 dpi (as matplotlib's sizes are given)
const BAR = 16, CB_GAP = 2, CB_BELOW = 8; // colour bar: its width, its gap from the plot, room under it
// frames waiting to be drawn, one per animation frame: a safety valve only (0.5 s at 60 Hz, or a
// hidden page, where animation frames stop), never reached while the page keeps up
const MAX_PENDING = 30;
// What the page's figures are doing, shared with the 3D views (scenes/static/scene_common.js):
// figures that hold a frame not yet painted, and when a figure last painted one. Without a GPU a
// 3D view's render takes 20-200 ms of the page's main thread; a view waits while a figure has a
// frame to paint, so the student's key press shows in the figure first and in the view a frame
// later.
const FRAMES = (globalThis.__afmsmilerFrames ??= { pending: 0, inputAt: -Infinity, paintedAt: -Infinity });

function el(tag, cls, parent) {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (parent) parent.appendChild(e);
  return e;
}

function font(size, weight) {
  return `${weight || ""} ${Math.round(size)}px sans-serif`.trim();
}

// -- series paths: lines with NaN gaps, in any order of x (uPlot's mode 2 gives each series its x),
// -- and markers ---------------------------------------------------------------------------------

function finitePos(u, v, key) {
  if (v == null || !Number.isFinite(v)) return NaN;
  const p = u.valToPos(v, key, true);
  return Number.isFinite(p) ? p : NaN;
}

function linePath(xKey, yKey) {
  return (u, si) => {
    const [xs, ys] = u.data[si];
    const stroke = new Path2D();
    let pen = false;
    for (let i = 0; i < xs.length; i++) {
      const px = finitePos(u, xs[i], xKey), py = finitePos(u, ys[i], yKey);
      if (Number.isNaN(px) || Number.isNaN(py)) { pen = false; continue; }
      if (pen) stroke.lineTo(px, py); else { stroke.moveTo(px, py); pen = true; }
    }
    return { stroke, fill: null, clip: null, band: null, gaps: null, flags: 0 };
  };
}

function markerPath(xKey, yKey, marker, size) {
  return (u, si) => {
    const [xs, ys] = u.data[si];
    const r = 0.5 * size * PX * devicePixelRatio;
    const stroke = new Path2D();
    const filled = marker === "o" || marker === "." || marker === "s" || marker === "D" ||
      marker === "^" || marker === "v";
    const fill = filled ? new Path2D() : null;
    for (let i = 0; i < xs.length; i++) {
      const x = finitePos(u, xs[i], xKey), y = finitePos(u, ys[i], yKey);
      if (Number.isNaN(x) || Number.isNaN(y)) continue;
      const shape = new Path2D();
      if (marker === "x") {
        shape.moveTo(x - r, y - r); shape.lineTo(x + r, y + r);
        shape.moveTo(x - r, y + r); shape.lineTo(x + r, y - r);
      } else if (marker === "+") {
        shape.moveTo(x - r, y); shape.lineTo(x + r, y);
        shape.moveTo(x, y - r); shape.lineTo(x, y + r);
      } else if (marker === "s") {
        shape.rect(x - r, y - r, 2 * r, 2 * r);
      } else if (marker === "D") {
        shape.moveTo(x, y - r); shape.lineTo(x + r, y); shape.lineTo(x, y + r);
        shape.lineTo(x - r, y); shape.closePath();
      } else if (marker === "^" || marker === "v") {
        const s = marker === "^" ? 1 : -1;
        shape.moveTo(x, y - s * r); shape.lineTo(x + r, y + s * r); shape.lineTo(x - r, y + s * r);
        shape.closePath();
      } else {
        shape.moveTo(x + r, y); shape.arc(x, y, r, 0, 2 * Math.PI);
      }
      stroke.addPath(shape);
      if (fill) fill.addPath(shape);
    }
    return { stroke, fill, clip: null, band: null, gaps: null, flags: 0 };
  };
}

// An axis label on one line (uPlot draws one), its font shrunk so that it fits the axis' length.
const measure = document.createElement("canvas").getContext("2d");
function fitLabel(axis, text, length) {
  const line = text.replace(/\s*\n\s*/g, " ");
  measure.font = font(12);
  const width = measure.measureText(line).width;
  const size = length > 0 && width > length ? Math.max(8, Math.floor(12 * length / width)) : 12;
  const css = font(size), px = Math.round(size * devicePixelRatio);
  if (axis.labelFont[0] !== css.replace(/(\d+)px/, `${px}px`)) {
    axis.labelFont = [css.replace(/(\d+)px/, `${px}px`), px, size];
  }
  return line;
}

// a legend's entries as HTML, rebuilt only when they change
function legendHtml(box, entries) {
  const key = JSON.stringify(entries);
  if (box.dataset.key === key) return;
  box.dataset.key = key;
  box.innerHTML = "";
  for (const e of entries) {
    const item = el("span", "afm-live-key", box);
    const sw = el("span", "afm-live-swatch", item);
    if (e.marker && !e.line) {
      sw.textContent = e.marker === "x" ? "\u00d7" : e.marker === "+" ? "+" : "\u25cf";
      sw.style.color = e.color;
    } else {
      sw.style.borderTop = `${Math.max(2, e.width || 2)}px ${e.dash ? "dashed" : "solid"} ${e.color}`;
    }
    el("span", "", item).textContent = e.label;
  }
}

// -- one axes: a uPlot with its title above and its legend below ---------------------------------

// Tick labels. uPlot's own kept 3 decimals and the browser's locale ("-0" at F = 0, "0,5",
// "-4,000"); these are plain decimals with as many digits as the tick step needs (a step of 2.5
// reads 2.5, 5, 7.5, never 3 and 8), and exponents for the very small and large.
function fmtTick(v, step) {
  return fmtTicks([v], step)[0];
}

// The power of ten of the last digit a step needs: 2 -> 0, 2.5 -> -1, 0.25 -> -2, 2.5e-4 -> -5,
// 500 -> 2. The step's mantissa is read to 6 significant digits (uPlot's steps are 1, 2, 2.5, 5
// times a power of ten, with float noise such as 0.30000000000000004).
function lastDigit(step) {
  const top = Math.floor(Math.log10(step) + 1e-9);
  let e = top;
  while (e > top - 6) {
    const m = step / Math.pow(10, e);
    if (Math.abs(m - Math.round(m)) <= 1e-6 * m) break;
    e -= 1;
  }
  return e;
}

// one format for all the labels of an axis: decimals down to the step's last digit, or, for steps
// below 1e-3 and values from 1e5, exponents with the mantissa digits down to that digit (each
// without trailing zeros)
function fmtTicks(values, step) {
  const finite = values.filter((v) => v != null && Number.isFinite(v));
  const big = Math.max(0, ...finite.map(Math.abs));
  if (!(step > 0)) step = finite.length > 1 ? Math.abs(finite[1] - finite[0]) : big || 1;
  const exponent = step < 1e-3 || big >= 1e5;
  const last = lastDigit(step);
  return values.map((v) => {
    if (v == null || !Number.isFinite(v)) return "";
    if (Math.abs(v) < 1e-9 * step) return "0";
    if (exponent) {
      const digits = Math.max(0, Math.min(6, Math.floor(Math.log10(Math.abs(v)) + 1e-9) - last));
      return v.toExponential(digits).replace(/\.?0+e/, "e").replace("e+", "e");
    }
    // to the step's last digit, without trailing zeros (2.5, 5, 7.5 as matplotlib's 2.5, 5.0)
    const text = v.toFixed(Math.max(0, Math.min(12, -last))).replace(/(\.\d*?)0+$/, "$1")
      .replace(/\.$/, "");
    return /^-0$/.test(text) ? "0" : text;
  });
}

// room for an axis' tick labels (uPlot's axis size): the widest label, its tick and a gap
function labelRoom(u, values, ai) {
  if (!values) return 30;
  measure.font = font(11);
  const widest = Math.max(0, ...values.map((v) => (v ? measure.measureText(v).width : 0)));
  const a = u.axes[ai];
  return Math.ceil(widest + a.ticks.size + a.gap + 8);
}

function isDecade(v) {
  const e = Math.log10(Math.abs(v));
  return Number.isFinite(e) && Math.abs(e - Math.round(e)) < 1e-9;
}

// Ticks of a log axis between min and max: every decade (labelled every k-th, k the same for
// all, so that labels fit) with 2..9 between them when few decades show. uPlot's own loop hung
// the page (34 s) for a lower limit just below a power of ten.
function logSplits(min, max) {
  if (!(min > 0 && max > min)) return [];
  const lo = Math.floor(Math.log10(min)), hi = Math.ceil(Math.log10(max));
  const decades = Math.min(hi - lo, 300), minor = decades <= 8, out = [];
  for (let e = lo; e <= lo + decades; e++) {
    for (let m = 1; m <= (minor ? 9 : 1); m++) {
      const v = m * Math.pow(10, e);
      if (v >= min * (1 - 1e-12) && v <= max * (1 + 1e-12)) out.push(v);
    }
  }
  return out;
}

// the mantissa of v (1..9) on a log axis' ticks
function mantissa(v) {
  return Math.round(v / Math.pow(10, Math.floor(Math.log10(v) + 1e-9)));
}

function logLabels(u, key, splits) {
  const decades = splits.filter(isDecade);
  const horizontal = u.scales[key].ori === 0;
  const length = horizontal ? u.bbox.width / devicePixelRatio : u.bbox.height / devicePixelRatio;
  const room = horizontal ? 42 : 16;
  const k = Math.max(1, Math.ceil(decades.length * room / Math.max(length, 1)));
  // an axis of two decades or less (0.2 to 12 nm) also reads 2 and 5 times each decade, as
  // matplotlib's: with its decades alone it read "1" and "10" and nothing below 1
  const sc = u.scales[key], span = Math.log10(sc.max / sc.min);
  const between = span <= 2 ? [2, 5] : [];
  return thin(u, key, splits, splits.map((v) => {
    if (!isDecade(v)) return between.includes(mantissa(v)) ? fmtTick(v) : "";
    const e = Math.round(Math.log10(v));
    return e % k === 0 ? fmtTick(v) : "";
  }));
}

// drop the labels that would overlap the one shown before them
function thin(u, key, splits, labels) {
  const horizontal = u.scales[key].ori === 0;
  const width = (text) => (horizontal ? text.length * 6.5 : 12);
  let last = -Infinity, lastWidth = 0;
  return labels.map((text, i) => {
    if (!text) return "";
    const p = u.valToPos(splits[i], key), w = width(text);
    if (Math.abs(p - last) < 0.5 * (w + lastWidth) + 6) return "";
    last = p; lastWidth = w;
    return text;
  });
}

// the kernel's limits, verbatim (uPlot pads and rounds a range it is asked for without data)
const exactRange = (u, min, max) => [min, max];

function scaleOpts(axis) {
  const s = { time: false, auto: false, range: exactRange };
  if (axis.scale === "log") Object.assign(s, { distr: 3, log: 10 });
  if (axis.scale === "symlog") Object.assign(s, { distr: 4, asinh: axis.linthresh || 1 });
  return s;
}

function axisOpts(scale, side, axis, show) {
  const a = {
    scale, side, show, label: axis.label || "", stroke: axis.color || "#222",
    labelFont: font(12), font: font(11), labelSize: 18, gap: 3, size: side % 2 ? 60 : 36,
    grid: { show: !!axis.grid && (side === 2 || side === 3), stroke: "#0000001a", width: 1 },
    ticks: { show: true, stroke: "#00000066", width: 1, size: 4 },
    filter: (u, splits) => splits, // every split reaches values(), which thins the labels itself
  };
  return a;
}

class Axes {
  constructor(fig, spec, cell) {
    this.fig = fig;
    this.spec = spec;
    this.cell = cell;
    this.title = el("div", "afm-live-title", cell);
    this.row = el("div", "afm-live-row", cell);
    this.plotBox = el("div", "afm-live-plot", this.row);
    this.legend = el("div", "afm-live-legend", cell);
    this.frame = null;
    this.images = [];
    const s = spec;
    const series = [{}];
    for (const sr of s.series) {
      const xKey = "x", yKey = sr.axis === "y2" ? "y2" : "y";
      const marker = sr.marker;
      const o = {
        label: "", stroke: sr.color, width: sr.width,
        dash: sr.dash ? sr.dash.map((d) => d * devicePixelRatio) : undefined,
        show: sr.visible !== false, spanGaps: false, points: { show: false },
        facets: [{ scale: xKey, auto: false }, { scale: yKey, auto: false }],
        paths: marker ? markerPath(xKey, yKey, marker, sr.size) : linePath(xKey, yKey),
      };
      if (marker && sr.filled) o.fill = sr.fill || sr.color;
      if (marker && !sr.line) { o.width = Math.max(sr.edge || 1, 1); o.dash = undefined; }
      series.push(o);
    }
    // uPlot's mode 2 takes its x scale from the first series: an axes holding only images gets
    // an empty one
    this.placeholder = s.series.length === 0;
    if (this.placeholder) {
      series.push({ label: "", stroke: "transparent", width: 0, points: { show: false },
        facets: [{ scale: "x", auto: false }, { scale: "y", auto: false }], paths: linePath("x", "y") });
    }
    const scales = { x: scaleOpts(s.x), y: scaleOpts(s.y) };
    const axes = [axisOpts("x", 2, s.x, s.x.show !== false), axisOpts("y", 3, s.y, s.y.show !== false)];
    if (s.y2) { scales.y2 = scaleOpts(s.y2); axes.push(axisOpts("y2", 1, s.y2, s.y2.visible !== false)); }
    if (s.x2) { scales.x2 = { time: false, auto: false, ori: 0, range: exactRange }; axes.push(axisOpts("x2", 0, s.x2, true)); }
    const self = this;
    this.u = new uPlot({
      mode: 2, width: 100, height: 100, pxAlign: 0, series, scales, axes,
      legend: { show: false }, cursor: { show: false, drag: { x: false, y: false } },
      select: { show: false },
      hooks: {
        drawClear: [(u) => self.drawUnder(u)],
        drawAxes: [(u) => self.drawRefs(u, false)],
        draw: [(u) => { self.drawRefs(u, true); self.drawFrame(u); self.drawOver(u); }],
      },
    }, [null, ...series.slice(1).map(() => [[], []])], this.plotBox);
    // uPlot's own tick placement and labels, for the axes whose ticks the kernel leaves free
    this.tickDefaults = this.u.axes.map((a) => [a.splits, a.values]);
    if (s.colorbar) {
      this.cbBox = el("div", "afm-live-colorbar", this.row);
      // the bar beside the plot box, as tall as it, BAR px wide (matplotlib's colour bar: a
      // twentieth of its height), its tick labels as wide as they are and its label beside them;
      // it was 80 px of chart with 78 px of fixed axis room, so a 2 px hairline
      this.cbWidth = BAR + 60;
      this.cb = new uPlot({
        mode: 2, width: this.cbWidth, height: 100,
        padding: [() => self.u.bbox.top / devicePixelRatio, null, CB_BELOW, CB_GAP],
        series: [{}, { stroke: "transparent", width: 0, points: { show: false },
          facets: [{ scale: "x", auto: false }, { scale: "c", auto: false }], paths: linePath("x", "c") }],
        scales: { x: { time: false, auto: false, range: exactRange },
          c: { time: false, auto: false, range: exactRange } },
        axes: [{ scale: "x", show: false }, Object.assign(axisOpts("c", 1, { label: s.colorbar.label }, true),
          { size: labelRoom, values: (u, sp, ai, space, incr) => thin(u, "c", sp, fmtTicks(sp, incr)) })],
        legend: { show: false }, cursor: { show: false }, select: { show: false },
        hooks: { drawClear: [(u) => self.drawColorbar(u)] },
      }, [null, [[], []]], this.cbBox);
      // uPlot hides an axis whose scale no series uses: keep it
      this.cb.axes[1].show = true;
    }
  }

  size(width, height) {
    this.cellSize = [width, height];
    const titleH = this.title.offsetHeight, legendH = this.legend.offsetHeight;
    const cbW = this.cb ? this.cbWidth : 0;
    const w = Math.max(60, width - cbW), h = Math.max(60, height - titleH - legendH - 4);
    this.full = [w, h];
    this.u.setSize({ width: w, height: h });
    this.fitColorbar();
  }

  // the colour bar's chart: its bar BAR px wide beside the plot box and as tall; true if its
  // width changed (the plot then gets the rest of the cell again)
  fitColorbar() {
    if (!this.cb) return false;
    const r = devicePixelRatio, u = this.u, cb = this.cb;
    const height = Math.round((u.bbox.top + u.bbox.height) / r + CB_BELOW);
    const around = cb.width - cb.bbox.width / r; // its padding, tick labels and label
    const width = Math.round(BAR + around);
    const changed = Math.abs(width - this.cbWidth) > 1, top = u.bbox.top;
    if (changed) this.cbWidth = width;
    if (top !== this.cbTop && !changed && height === cb.height) {
      // the plot box moved down as much as it shrank: uPlot lays out again only on a new size
      cb.setSize({ width: this.cbWidth, height: height + 1 });
    }
    this.cbTop = top;
    if (changed || height !== cb.height) cb.setSize({ width: this.cbWidth, height });
    return changed;
  }

  update(frame, buf) {
    this.frame = frame;
    const s = this.spec;
    // title and legend (HTML), touched only when they change: the page's layout stays put
    const title = frame.title ? frame.title.text : "", color = frame.title ? frame.title.color : "";
    if (title !== this.shownTitle || color !== this.shownColor) {
      this.title.textContent = title;
      this.title.style.color = color || "";
      this.shownTitle = title; this.shownColor = color;
    }
    legendHtml(this.legend, frame.legend || []);
    const keys = [["x", 0], ["y", 1]];
    if (s.y2) keys.push(["y2", 2]);
    if (s.x2) keys.push(["x2", s.y2 ? 3 : 2]);
    for (const [key, i] of keys) {
      const axis = frame.axes[key];
      const a = this.u.axes[i], [splits, values] = this.tickDefaults[i];
      const horizontal = key === "x" || key === "x2";
      const length = (horizontal ? this.u.bbox.width : this.u.bbox.height) / devicePixelRatio;
      a.label = fitLabel(a, axis.label || "", length);
      a.stroke = () => axis.color || "#222";
      const scale = (s[key] && s[key].scale) || "linear";
      if (scale === "symlog") this.u.scales[key].asinh = axis.linthresh || 1;
      // ticks the kernel chose (a FixedLocator) with its labels; log axes by decades; else
      // uPlot's placement with our labels
      if (axis.ticks) {
        const labels = axis.ticklabels || axis.ticks.map((v) => fmtTick(v));
        a.splits = () => axis.ticks;
        a.values = (u, sp) => thin(u, key, sp, labels);
      } else if (scale === "log") {
        a.splits = (u, ai, min, max) => logSplits(min, max);
        a.values = (u, sp) => logLabels(u, key, sp);
      } else {
        a.splits = splits;
        a.values = (u, sp, ai, space, incr) => thin(u, key, sp, fmtTicks(sp, incr));
      }
    }
    // data
    const data = [null];
    for (const d of frame.series) {
      data.push([buf.subarray(d.x[0], d.x[0] + d.x[1]), buf.subarray(d.y[0], d.y[0] + d.y[1])]);
    }
    if (this.placeholder) data.push([[], []]);
    this.images = (frame.images || []).map((im) => this.image(im, buf));
    const lim = {};
    for (const [key] of keys) lim[key] = frame.axes[key].lim.slice();
    if (s.aspect === "equal") this.equalAspect(lim);
    this.u.batch(() => {
      this.u.setData(data, false);
      for (const key in lim) {
        // a reversed pair of limits (set_xlim(1, 0)) runs the axis the other way
        const [a, b] = lim[key];
        this.u.scales[key].dir = a > b ? -1 : 1;
        this.u.setScale(key, { min: Math.min(a, b), max: Math.max(a, b) });
      }
      this.u.redraw(false, true);
    });
    if (this.cb && frame.colorbar) {
      const c = frame.colorbar;
      // its label on one line, shrunk to the bar's length ("friction coefficient mu
      // (dimensionless)" ran off both ends)
      this.cb.axes[1].label = fitLabel(this.cb.axes[1], c.label || "",
        this.cb.bbox.height / devicePixelRatio);
      this.cb.batch(() => {
        this.cb.setScale("x", { min: 0, max: 1 });
        this.cb.setScale("c", { min: c.vmin, max: c.vmax });
        this.cb.redraw(false, true);
      });
      // new tick labels may need more or less room: the bar keeps its width
      // (once: labels that changed again with the new size keep the bar a pixel off)
      if (!this.refitting && this.fitColorbar() && this.cellSize) {
        this.refitting = true;
        try { this.size(...this.cellSize); this.update(frame, buf); } finally { this.refitting = false; }
      }
    }
  }

  // equal aspect as matplotlib's adjustable="box": the plot box shrinks, the limits stay
  equalAspect(lim) {
    if (!this.full) return;
    const [w, h] = this.full, u = this.u, r = devicePixelRatio;
    const extraW = u.width - u.bbox.width / r, extraH = u.height - u.bbox.height / r;
    const bw = w - extraW, bh = h - extraH; // the plot box the whole cell would give
    const ratio = Math.abs((lim.x[1] - lim.x[0]) / (lim.y[1] - lim.y[0]));
    if (!(bw > 0 && bh > 0 && Number.isFinite(ratio) && ratio > 0)) return;
    let pw = bw, ph = bh;
    if (bw / bh > ratio) pw = bh * ratio; else ph = bw / ratio;
    const size = { width: Math.round(pw + extraW), height: Math.round(ph + extraH) };
    if (size.width !== u.width || size.height !== u.height) {
      u.setSize(size);
      this.fitColorbar();
    }
  }

  image(im, buf) {
    const [ny, nx] = im.shape;
    const values = buf.subarray(im.data[0], im.data[0] + nx * ny);
    const lut = this.fig.lut(im.cmap);
    const canvas = document.createElement("canvas");
    canvas.width = nx; canvas.height = ny;
    const ctx = canvas.getContext("2d");
    const img = ctx.createImageData(nx, ny);
    const span = im.vmax - im.vmin || 1;
    for (let r = 0; r < ny; r++) {
      const row = im.origin === "lower" ? ny - 1 - r : r; // the data row drawn at canvas row r
      for (let c = 0; c < nx; c++) {
        const v = values[row * nx + c], o = 4 * (r * nx + c);
        if (!Number.isFinite(v)) { img.data[o + 3] = 0; continue; }
        const k = Math.max(0, Math.min(255, Math.round(255 * (v - im.vmin) / span)));
        img.data[o] = lut[3 * k]; img.data[o + 1] = lut[3 * k + 1]; img.data[o + 2] = lut[3 * k + 2];
        img.data[o + 3] = 255;
      }
    }
    ctx.putImageData(img, 0, 0);
    return { canvas, extent: im.extent };
  }

  // spans and images, under everything
  drawUnder(u) {
    const f = this.frame;
    if (!f) return;
    const ctx = u.ctx, bb = u.bbox;
    ctx.save();
    ctx.beginPath(); ctx.rect(bb.left, bb.top, bb.width, bb.height); ctx.clip();
    for (const im of this.images) {
      const [x0, x1, y0, y1] = im.extent;
      const px0 = u.valToPos(x0, "x", true), px1 = u.valToPos(x1, "x", true);
      const py0 = u.valToPos(y0, "y", true), py1 = u.valToPos(y1, "y", true);
      ctx.imageSmoothingEnabled = false;
      ctx.drawImage(im.canvas, Math.min(px0, px1), Math.min(py0, py1), Math.abs(px1 - px0),
        Math.abs(py1 - py0));
    }
    for (const sp of f.spans || []) {
      ctx.fillStyle = sp.color;
      if (sp.kind === "v") {
        const a = this.clampPos(u, sp.lo, "x"), b = this.clampPos(u, sp.hi, "x");
        ctx.fillRect(Math.min(a, b), bb.top, Math.abs(b - a), bb.height);
      } else {
        const key = sp.axis || "y";
        const a = this.clampPos(u, sp.lo, key), b = this.clampPos(u, sp.hi, key);
        ctx.fillRect(bb.left, Math.min(a, b), bb.width, Math.abs(b - a));
      }
    }
    ctx.restore();
  }

  clampPos(u, v, key) {
    const sc = u.scales[key];
    const lo = Math.min(sc.min, sc.max), hi = Math.max(sc.min, sc.max);
    return u.valToPos(Math.max(lo, Math.min(hi, v)), key, true);
  }

  // reference lines, under the curves or over them (as matplotlib stacks them: zorder, order)
  drawRefs(u, over) {
    const f = this.frame;
    if (!f) return;
    const ctx = u.ctx, bb = u.bbox, r = devicePixelRatio;
    ctx.save();
    ctx.beginPath(); ctx.rect(bb.left, bb.top, bb.width, bb.height); ctx.clip();
    for (const ln of f.refs || []) {
      if (!!ln.over !== over) continue;
      ctx.strokeStyle = ln.color; ctx.lineWidth = ln.width * r;
      ctx.setLineDash((ln.dash || []).map((d) => d * r));
      ctx.beginPath();
      if (ln.kind === "v") {
        const x = u.valToPos(ln.at, "x", true);
        ctx.moveTo(x, bb.top + (1 - ln.to) * bb.height); ctx.lineTo(x, bb.top + (1 - ln.from) * bb.height);
      } else {
        const y = u.valToPos(ln.at, ln.axis || "y", true);
        ctx.moveTo(bb.left + ln.from * bb.width, y); ctx.lineTo(bb.left + ln.to * bb.width, y);
      }
      ctx.stroke();
    }
    ctx.restore();
  }

  // the axes' frame (matplotlib's spines)
  drawFrame(u) {
    if (this.spec.x.show === false && this.spec.y.show === false) return;
    const ctx = u.ctx, bb = u.bbox, r = devicePixelRatio;
    ctx.save();
    ctx.strokeStyle = "#000"; ctx.lineWidth = 0.8 * r; ctx.setLineDash([]);
    ctx.strokeRect(bb.left, bb.top, bb.width, bb.height);
    ctx.restore();
  }

  // texts, over everything
  drawOver(u) {
    const f = this.frame;
    if (!f) return;
    const ctx = u.ctx, bb = u.bbox, r = devicePixelRatio;
    ctx.save();
    for (const t of f.texts || []) {
      if (!t.text) continue;
      let x, y;
      if (t.coords === "axes") { x = bb.left + t.x * bb.width; y = bb.top + (1 - t.y) * bb.height; }
      else { x = u.valToPos(t.x, "x", true); y = u.valToPos(t.y, "y", true); }
      ctx.fillStyle = t.color || "#222";
      ctx.font = font(t.size * r);
      ctx.textAlign = t.ha === "center" ? "center" : t.ha === "right" ? "right" : "left";
      const lines = t.text.split("\n"), lh = 1.2 * t.size * r;
      const top = t.va === "top" ? y : t.va === "center" ? y - 0.5 * lh * (lines.length - 1)
        : y - lh * (lines.length - 1);
      ctx.textBaseline = t.va === "top" ? "top" : t.va === "center" ? "middle" : "alphabetic";
      lines.forEach((line, i) => ctx.fillText(line, x, top + i * lh));
    }
    ctx.restore();
  }

  drawColorbar(u) {
    const f = this.frame;
    if (!f || !f.colorbar) return;
    const lut = this.fig.lut(f.colorbar.cmap), bb = u.bbox, ctx = u.ctx;
    const n = 256, h = bb.height / n;
    for (let k = 0; k < n; k++) {
      ctx.fillStyle = `rgb(${lut[3 * k]},${lut[3 * k + 1]},${lut[3 * k + 2]})`;
      ctx.fillRect(bb.left, bb.top + bb.height - (k + 1) * h, bb.width, h + 1);
    }
  }

  destroy() {
    this.u.destroy();
    if (this.cb) this.cb.destroy();
  }
}

// -- the figure: a grid of axes, a suptitle and a figure legend ------------------------------------

function decodeLut(b64) {
  const s = atob(b64), out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

// append v to a log of the last few hundred values
// Run f in a task after the current one: posted from an animation-frame callback, after that
// frame's rendering update (style, layout, paint, commit), which ends the task the callback runs in.
const afterChannel = new MessageChannel(), afterQueue = [];
afterChannel.port1.onmessage = () => { for (const f of afterQueue.splice(0)) f(); };
function afterRendering(f) {
  afterQueue.push(f);
  if (afterQueue.length === 1) afterChannel.port2.postMessage(null);
}

function keep(log, v) {
  log.push(v);
  if (log.length > 1000) log.splice(0, 500);
}

class Figure {
  constructor(root) {
    this.root = root;
    root.classList.add("afm-live");
    root.dataset.frames = "0";
    root.afmFigure = this; // for the browser tests and the console
    this.layoutKey = null;
    this.axes = [];
    this.luts = {};
    this.pending = [];
    this.scheduled = false;
    this.drawnSeq = null; // drawn in an animation frame, not yet known painted (see tick)
    this.received = 0; // frames received from the kernel (push)
    this.painted = 0; // frames known painted
    // the kernel's sequence numbers of the last frames received and painted, in order (the
    // browser tests compare them: every frame received is painted once)
    this.receivedSeqs = [];
    this.paintedSeqs = [];
    this.drawnAt = null; // the requestAnimationFrame time of the last frame drawn
    root.dataset.painted = "0";
  }

  lut(name) { return this.luts[name] || new Uint8Array(768); }

  build(layout) {
    for (const a of this.axes) a.destroy();
    this.root.innerHTML = "";
    // a static page narrower than the figure (a book's column) gets the figure scaled to fit
    const avail = this.fit && this.root.parentElement ? this.root.parentElement.clientWidth : 0;
    const k = avail > 200 && avail < layout.width ? avail / layout.width : 1;
    this.layout = Object.assign({}, layout, { width: layout.width * k, height: layout.height * k });
    const L = this.layout;
    this.root.style.width = `${L.width}px`;
    // its size while out of view (live.css: content-visibility), the last one drawn once drawn
    this.root.style.containIntrinsicSize = `auto ${L.width}px auto ${L.height}px`;
    this.header = el("div", "afm-live-header", this.root);
    this.suptitle = el("div", "afm-live-suptitle", this.header);
    this.figLegend = el("div", "afm-live-legend", this.header);
    this.grid = el("div", "afm-live-grid", this.root);
    this.grid.style.gridTemplateColumns = L.col_ratios.map((r) => `${r}fr`).join(" ");
    this.grid.style.gridTemplateRows = L.row_ratios.map((r) => `${r}fr`).join(" ");
    this.axes = L.axes.map((spec) => {
      const cell = el("div", "afm-live-cell", this.grid);
      cell.style.gridColumn = `${spec.col + 1} / span ${spec.colspan}`;
      cell.style.gridRow = `${spec.row + 1} / span ${spec.rowspan}`;
      if (spec.visible === false) cell.style.visibility = "hidden";
      return new Axes(this, spec, cell);
    });
  }

  // the heights of the texts around the plots (0 while the figure is not in the page yet)
  chromeHeights() {
    return [this.header.offsetHeight, ...this.axes.map((a) => a.title.offsetHeight + a.legend.offsetHeight)].join();
  }

  // The texts around the plots keep the tallest height they had since the layout was built: a
  // line that comes and goes (a coarse answer's status above its maps, gone from the full answer
  // that follows) no longer moves the plots under the student's eyes, nor lays them out again and
  // draws them twice on each frame (a force-volume frame took 15 ms of the page for it).
  holdChrome() {
    for (const e of [this.header, ...this.axes.flatMap((a) => [a.title, a.legend])]) {
      const h = e.offsetHeight;
      if (h > (e.afmHeld || 0)) {
        e.afmHeld = h;
        e.classList.add("afm-held");
        e.style.boxSizing = "border-box";
        e.style.minHeight = `${h}px`;
      }
    }
  }

  // shown after it was drawn detached (a collapsed output, a tab shown later): measure again
  watch() {
    if (this.observer || typeof ResizeObserver === "undefined") return;
    this.observer = new ResizeObserver(() => {
      if (!this.last || this.chromeHeights() === this.measured) return;
      this.measured = this.chromeHeights();
      this.resize();
      this.last[1].axes.forEach((f, i) => this.axes[i].update(f, this.last[2]));
    });
    this.observer.observe(this.root);
  }

  resize() {
    const L = this.layout;
    const headerH = this.header.offsetHeight;
    const gridH = Math.max(100, L.height - headerH);
    this.grid.style.height = `${gridH}px`;
    const gap = 8, colSum = L.col_ratios.reduce((a, b) => a + b, 0);
    const rowSum = L.row_ratios.reduce((a, b) => a + b, 0);
    const span = (ratios, start, n) => ratios.slice(start, start + n).reduce((a, b) => a + b, 0);
    for (const a of this.axes) {
      const s = a.spec;
      const w = (L.width - gap * (L.col_ratios.length - 1)) * span(L.col_ratios, s.col, s.colspan)
        / colSum + gap * (s.colspan - 1);
      const h = (gridH - gap * (L.row_ratios.length - 1)) * span(L.row_ratios, s.row, s.rowspan)
        / rowSum + gap * (s.rowspan - 1);
      a.size(w, h);
    }
  }

  // A frame from the kernel: drawn at the next animation frame, one frame per animation frame.
  //
  // A requestAnimationFrame callback runs just before the browser's rendering update of that
  // frame (style, layout, paint), so a canvas drawn in it is painted in that same update; drawing
  // from the message handler instead lets a second message of the same frame overwrite the first
  // draw before it was ever painted (the old scheduler reset its "painted" flag at the start of an
  // animation frame and then drew a queued frame in it too). Drawing here costs no latency: the
  // first chance to paint a frame is that rendering update anyway. The frame is known painted
  // once that rendering update has run: a task posted from the callback runs after it (the
  // update finishes the task the callback runs in), or, if the page's tasks wait behind input, the
  // next callback finds the frame still unrecorded and records it (a rendering update came
  // between them). data-painted and paintedSeqs count paints, not draws; the kernel hears of
  // each at once, not an animation frame later.
  //
  // Queued frames are never dropped for newer ones while the page keeps up: the kernel already
  // computed each of them (it coalesces a drag's moves before running the model, so it sends only
  // frames of values the student passed while it was free, and the last one for where the
  // student stopped), and a frame dropped here would be a step the student never sees. Only a
  // hidden page (no animation frames) or a backlog past MAX_PENDING keeps the newest alone.
  push(layout, frame, buffer) {
    this.received += 1;
    keep(this.receivedSeqs, frame.seq);
    this.pending.push([layout, frame, buffer]);
    if (this.pending.length > MAX_PENDING || document.hidden) this.pending = this.pending.slice(-1);
    if (!this.holding) { this.holding = true; FRAMES.pending += 1; }
    this.schedule();
  }

  // nothing left to draw or paint: the 3D views may render again
  release(ts) {
    FRAMES.paintedAt = ts;
    if (!this.holding) return;
    this.holding = false;
    FRAMES.pending = Math.max(0, FRAMES.pending - 1);
  }

  schedule() {
    if (this.scheduled) return;
    this.scheduled = true;
    requestAnimationFrame((ts) => this.tick(ts));
  }

  // the frame drawn last has been through a rendering update: record its paint (once)
  paintedNow() {
    if (this.drawnSeq === null) return;
    keep(this.paintedSeqs, this.drawnSeq);
    this.painted += 1;
    this.root.dataset.painted = String(this.painted);
    this.drawnSeq = null;
  }

  tick(ts) {
    this.scheduled = false;
    this.paintedNow(); // drawn in an earlier animation frame and not yet recorded
    if (!this.pending.length) { this.release(ts); return; }
    const [layout, frame, buffer] = this.pending.shift();
    // then the next frame, and the paint of this one (a frame that failed to draw does not stop
    // the ones after it)
    try {
      this.draw(layout, frame, buffer);
      this.drawnSeq = frame.seq === undefined ? -1 : frame.seq;
      // the time of the animation frame that paints it (the browser tests date a change by it)
      this.drawnAt = ts;
      // the kernel hears of it from this callback, whose rendering update paints it: it sends no
      // frame while two are unpainted (LiveFigure.busy, FRAMES_AHEAD), so a page slower than the
      // kernel gets the newest frame, not a queue of steps already passed. Told from the task
      // after the rendering update instead, it heard 20-50 ms late in a drag (the page's tasks
      // wait behind its input and rendering), and held the last key's frame back as long.
      if (this.onPainted && this.drawnSeq > 0) this.onPainted(this.drawnSeq);
      afterRendering(() => this.paintedNow());
    } finally {
      this.schedule();
    }
  }

  draw(layout, frame, buffer) {
    const key = JSON.stringify(layout);
    for (const [name, b64] of Object.entries(layout.luts || {})) {
      if (!this.luts[name]) this.luts[name] = decodeLut(b64);
    }
    const rebuilt = key !== this.layoutKey;
    if (rebuilt) { this.build(layout); this.layoutKey = key; }
    this.suptitle.textContent = frame.suptitle || "";
    legendHtml(this.figLegend, frame.legend || []);
    // titles and legends first: their heights set the plots' sizes
    frame.axes.forEach((f, i) => this.axes[i].update(f, buffer));
    this.holdChrome();
    const heights = this.chromeHeights();
    if (rebuilt || heights !== this.measured) {
      this.measured = heights;
      this.resize();
      frame.axes.forEach((f, i) => this.axes[i].update(f, buffer));
    }
    this.last = [layout, frame, buffer];
    this.root.dataset.frames = String(Number(this.root.dataset.frames) + 1);
    this.root.dataset.seq = String(frame.seq);
  }
}

function floats(view) {
  if (!view) return new Float32Array(0);
  const bytes = view.buffer.slice(view.byteOffset, view.byteOffset + view.byteLength);
  return new Float32Array(bytes);
}

// The static copy of a figure (static_html) sits beside its widget in the same output area, for the
// pages where no widget manager runs (an export without network, a saved notebook without kernel).
// Wherever the live figure is drawn, its static copy steps aside.
function outputArea(node) {
  return node.isConnected ? node.closest(".jp-OutputArea, .output_area, .output, .cell") : null;
}

// once the view is in the page (a few tries): hide the static copies of its output area, and mark
// its notebook, whose cells are then painted each on its own (live.css: .afm-notebook)
function settleIn(node, tries = 60) {
  const area = outputArea(node);
  if (!area) {
    if (tries > 0) requestAnimationFrame(() => settleIn(node, tries - 1));
    return;
  }
  for (const copy of area.querySelectorAll(".afm-live-static")) copy.style.display = "none";
  const notebook = area.closest(".jp-Notebook");
  if (notebook && !notebook.classList.contains("afm-notebook")) notebook.classList.add("afm-notebook");
}

function liveBeside(node) {
  const area = outputArea(node);
  if (!area) return false;
  for (const fig of area.querySelectorAll(".afm-live")) {
    if (!fig.closest(".afm-live-static")) return true;
  }
  return false;
}

// anywidget's entry point: a view of the LiveFigure widget
function render({ model, el: host }) {
  const root = document.createElement("div");
  host.appendChild(root);
  requestAnimationFrame(() => settleIn(host));
  const fig = new Figure(root);
  fig.watch();
  fig.onPainted = (seq) => {
    try { model.send({ painted: seq }); } catch (e) { fig.onPainted = null; }
  };
  const show = () => fig.push(model.get("_layout"), model.get("_frame"), floats(model.get("_buffer")));
  model.on("change:_frame", show);
  // the first frame once the element is in the page (sizes are measured)
  requestAnimationFrame(show);
  return () => {
    model.off("change:_frame", show);
    if (fig.observer) fig.observer.disconnect();
    for (const a of fig.axes) a.destroy();
  };
}

// a static page (an exported notebook, the book): the frame is embedded in the page
function drawStatic(root, layout, frame, base64) {
  const copy = root.closest(".afm-live-static") || root;
  if (liveBeside(copy)) { copy.style.display = "none"; return null; }
  const s = atob(base64), bytes = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
  const fig = new Figure(root);
  fig.fit = true;
  fig.draw(layout, frame, new Float32Array(bytes.buffer));
  return fig;
}

export default { render };
export { drawStatic };
