// The widget of a 3D view (SceneView): commands arrive as comm messages of the model, each a
// list of command descriptions with one msgpack buffer per command. The model (not a view) keeps
// the scene as the last command of each kind per path, in the order of change (the kernel's
// SceneState, mirrored), so a view displayed later, or a second view of the same widget, is
// replayed the scene at once; when the page was reloaded the model asks the kernel for a replay.

const LOAD_TIMEOUT_MS = 20000;

function afmMeshCat() {
  const hub = (globalThis.__afmsmilerMeshCat ??= {});
  if (hub.MeshCat) return Promise.resolve(hub.MeshCat);
  if (!hub.promise) hub.promise = new Promise((resolve) => { hub.resolve = resolve; });
  return Promise.race([hub.promise, new Promise((_, reject) => setTimeout(
    () => reject(new Error("meshcat's viewer did not load (the library widget is missing)")),
    LOAD_TIMEOUT_MS))]);
}

// uid of the kernel's SceneView -> { entries: Map, seq, views: Set } (anywidget hands initialize
// and render different wrappers of one model, so the kernel's id is the key)
const SCENES = new Map();

function sceneOf(model) {
  const uid = model.get("_uid");
  let s = SCENES.get(uid);
  if (!s) { s = { entries: new Map(), seq: 0, views: new Set(), queue: [], flushing: false }; SCENES.set(uid, s); }
  return s;
}

function record(s, cmd, bytes) {
  const { kind, path, prop } = cmd;
  if (kind === "delete") {
    const below = path.replace(/\/+$/, "") + "/";
    for (const [key, e] of s.entries) {
      if (e.path === path || e.path.startsWith(below)) s.entries.delete(key);
    }
    return;
  }
  if (kind === "set_object") {
    for (const [key, e] of s.entries) {
      if (e.kind === "set_property" && e.path === path) s.entries.delete(key);
    }
  }
  const key = `${kind}\u0000${path}\u0000${prop}`;
  s.entries.delete(key);
  s.entries.set(key, { kind, path, bytes });
}

// A slider's move sends the panel's figure first and its 3D view's commands after it. Decoding a
// scene's commands (a stress-coloured lever is a 120 kB mesh) takes the page's thread for
// milliseconds, so the views apply them after the next paint: the figure's frame, drawn at the
// next animation frame, is painted first.
function applyAfterPaint(s) {
  if (s.flushing) return;
  s.flushing = true;
  requestAnimationFrame(() => setTimeout(() => {
    s.flushing = false;
    const queued = s.queue.splice(0);
    for (const bytes of queued) for (const view of s.views) view.apply(bytes);
  }, 0));
}

function initialize({ model }) {
  const s = sceneOf(model);
  const onMessage = (content, buffers) => {
    if (!content || !Array.isArray(content.commands)) return;
    const bufs = buffers || [];
    if (content.type === "replay") {
      s.entries.clear();
      s.queue.length = 0; // the replay holds them
      content.commands.forEach((c, i) => record(s, c, afmBytes(bufs[i])));
      s.seq = content.seq;
      for (const view of s.views) view.reset();
      return;
    }
    content.commands.forEach((c, i) => {
      if (c.seq <= s.seq) return; // already in a replay
      const bytes = afmBytes(bufs[i]);
      record(s, c, bytes);
      s.seq = c.seq;
      s.queue.push(bytes);
    });
    applyAfterPaint(s);
  };
  model.on("msg:custom", onMessage);
  // commands sent before this model existed in the page (a reload, a late view) come back whole
  model.send({ type: "replay" });
  return () => { model.off("msg:custom", onMessage); SCENES.delete(model.get("_uid")); };
}

function render({ model, el }) {
  const s = sceneOf(model);
  const host = document.createElement("div");
  host.className = "afm-scene";
  host.style.height = `${model.get("height")}px`;
  el.appendChild(host);
  const note = document.createElement("div");
  note.className = "afm-scene-note";
  note.textContent = "loading the 3D view ...";
  host.appendChild(note);
  let view = null, disposed = false;
  const handle = {
    apply(bytes) {
      if (!view) return;
      view.apply(bytes);
      host.dataset.commands = String(s.entries.size);
      host.dataset.applied = String(Number(host.dataset.applied || 0) + 1);
    },
    reset() {
      if (!view) return;
      view.dispose();
      build();
    },
  };
  const overlays = () => {
    if (!view) return;
    view.setLegend(model.get("legend"));
    view.setLabels(model.get("_labels"));
  };
  let MeshCat = null;
  const build = () => {
    view = afmCreateViewer(MeshCat, host);
    for (const e of s.entries.values()) view.apply(e.bytes);
    overlays();
    host.dataset.commands = String(s.entries.size);
    host.dataset.applied = String(Number(host.dataset.applied || 0) + s.entries.size);
    host.afmView = view; // for the browser tests
  };
  afmMeshCat().then((lib) => {
    if (disposed) return;
    MeshCat = lib;
    note.remove();
    build();
    s.views.add(handle);
  }).catch((err) => { note.textContent = `The 3D view could not start: ${err.message}`; });
  const onHeight = () => { host.style.height = `${model.get("height")}px`; };
  model.on("change:height", onHeight);
  model.on("change:legend", overlays);
  model.on("change:_labels", overlays);
  return () => {
    disposed = true;
    s.views.delete(handle);
    model.off("change:height", onHeight);
    model.off("change:legend", overlays);
    model.off("change:_labels", overlays);
    if (view) view.dispose();
  };
}

export default { initialize, render };
