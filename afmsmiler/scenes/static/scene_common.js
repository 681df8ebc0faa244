// The browser side of afmsmiler's 3D views (afmsmiler/scenes/view.py), shared by the widget and
// the static page: meshcat's own three.js viewer (MeshCat.Viewer, from the meshcat package's
// main.min.js) drawn in an element of the page, sized by that element, with screen-space text
// over it (a legend in a corner, labels pinned to points of the scene).
//
// The scene arrives as meshcat's own msgpack commands; this file holds no physics and builds no
// geometry: every object comes from the kernel's scene builders.

function afmBytes(b) {
  if (b instanceof Uint8Array) return b;
  if (b instanceof ArrayBuffer) return new Uint8Array(b);
  return new Uint8Array(b.buffer, b.byteOffset, b.byteLength); // a DataView
}

// What the page's live figures are doing (plots/static/live.js fills it: figures holding a frame
// not yet painted, the time of the last paint) and when the student last pressed a key or clicked
// outside a 3D view (a slider, most likely), shared by every view of the page.
function afmFrames() {
  const frames = (globalThis.__afmsmilerFrames ??= { pending: 0, inputAt: -Infinity, paintedAt: -Infinity });
  if (!frames.listening && typeof document !== "undefined") {
    frames.listening = true;
    const input = (event) => {
      const target = event.target;
      if (target && target.closest && target.closest(".afm-scene")) return; // turning a view
      frames.inputAt = performance.now();
    };
    document.addEventListener("keydown", input, true);
    document.addEventListener("pointerdown", input, true);
  }
  return frames;
}

// A meshcat viewer in `host` (an element with a size), with its overlays; returns its handle.
function afmCreateViewer(MeshCat, host) {
  host.classList.add("afm-scene");
  const pane = document.createElement("div");
  pane.className = "afm-scene-pane";
  host.appendChild(pane);
  const viewer = new MeshCat.Viewer(pane);
  // meshcat sizes its canvas by the window (its own page is the whole window); here the host
  // element decides, whatever asks (meshcat's window listener, our observer)
  const setSize = viewer.set_3d_pane_size.bind(viewer);
  viewer.set_3d_pane_size = (w, h) => setSize(w === undefined ? Math.max(1, host.clientWidth) : w,
                                               h === undefined ? Math.max(1, host.clientHeight) : h);
  const legend = document.createElement("div");
  legend.className = "afm-scene-legend";
  host.appendChild(legend);
  const labels = document.createElement("div");
  labels.className = "afm-scene-labels";
  host.appendChild(labels);
  let pins = [];
  const v = new MeshCat.THREE.Vector3();
  const placeLabels = () => {
    const cam = viewer.camera, w = host.clientWidth, h = host.clientHeight;
    if (!cam) return;
    viewer.scene.updateMatrixWorld();
    for (const pin of pins) {
      // a point of the scene (z up) through meshcat's scene root (three.js is y up) to the screen
      v.set(pin.at[0], pin.at[1], pin.at[2]).applyMatrix4(viewer.scene.matrixWorld).project(cam);
      const visible = v.z < 1 && Math.abs(v.x) <= 1.2 && Math.abs(v.y) <= 1.2;
      pin.el.style.display = visible ? "" : "none";
      pin.el.style.left = `${((v.x + 1) / 2) * w}px`;
      pin.el.style.top = `${((1 - v.y) / 2) * h}px`;
    }
  };
  // afmsmiler's own command beside meshcat's: frame the objects under a path (SceneView's
  // fit_camera), keeping the camera's direction
  const fitTo = (path, margin, points) => {
    const THREE = MeshCat.THREE, cam = viewer.camera, controls = viewer.controls;
    viewer.scene.updateMatrixWorld(true);
    let box;
    if (points) { // the scene's world (z up) through meshcat's root to three.js's world
      box = new THREE.Box3().setFromPoints(points.map((p) =>
        new THREE.Vector3(p[0], p[1], p[2]).applyMatrix4(viewer.scene.matrixWorld)));
    } else {
      const node = viewer.scene_tree.find(path.split("/").filter((x) => x.length > 0));
      box = new THREE.Box3().setFromObject(node.object);
    }
    if (box.isEmpty() || !cam || !controls) return;
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const centre = cam.parent ? cam.parent.worldToLocal(sphere.center.clone()) : sphere.center;
    const dir = cam.position.clone().sub(controls.target);
    if (dir.lengthSq() === 0) dir.set(1, 1, 1);
    dir.normalize();
    const vfov = (cam.fov * Math.PI) / 180;
    const fov = Math.min(vfov, 2 * Math.atan(Math.tan(vfov / 2) * Math.max(cam.aspect, 1e-3)));
    const dist = (margin * sphere.radius) / Math.sin(fov / 2);
    controls.target.copy(centre);
    cam.position.copy(centre).addScaledVector(dir, dist);
    cam.near = Math.max(1e-5, dist / 1000);
    cam.far = Math.max(100, dist * 100);
    cam.updateProjectionMatrix();
    controls.update();
  };
  // the last fit is made again when the view changes size (it is often made before the page
  // has laid the view out), until the student turns the camera
  let lastFit = null, turned = false;
  if (viewer.controls) viewer.controls.addEventListener("start", () => { turned = true; });
  const refit = () => {
    if (!lastFit || turned) return;
    fitTo(lastFit.path, lastFit.margin || 1, lastFit.points);
    viewer.set_dirty();
  };
  const handle = viewer.handle_command.bind(viewer);
  viewer.handle_command = (cmd) => {
    if (cmd && cmd.type === "afm_fit") {
      lastFit = cmd;
      turned = false;
      refit();
    } else handle(cmd);
  };
  const render = viewer.render.bind(viewer);
  viewer.render = () => { render(); placeLabels(); };
  const observer = typeof ResizeObserver === "function"
    ? new ResizeObserver(() => { viewer.set_3d_pane_size(); refit(); }) : null;
  if (observer) observer.observe(host);
  viewer.set_3d_pane_size();
  let running = true;
  // meshcat renders on every animation frame while an animation plays. Without a GPU (software
  // WebGL) a rendered frame of a view delays the page's next frame by 100-200 ms, so a playing
  // animation took every frame from the page: a panel's figure painted none of a 15-step drag
  // and each key press waited about a second. Here a view renders only while on screen, and a
  // render's cost is the page's time from the render to the end of that frame's rendering
  // update (measured in a task posted from the animation frame, which runs after it). That
  // includes the commit: with software compositing (headless Chromium, a machine without a GPU)
  // the compositor reads the WebGL canvas back (20-25 ms a render on a 2-core machine), which
  // the time to the next animation frame does not show.
  // After a render a view waits RENDER_WAIT times its cost less one frame, so a view takes about
  // a quarter of the page's main thread at most where a render is dear, and renders every frame
  // where it is cheap (under a third of a frame: a GPU).
  //
  // A key press or a click outside the 3D views (a slider moved) holds the views' renders until
  // the figures painted what it changed: while a live figure (plots/static/live.js) has a frame to
  // paint, or for INPUT_HOLD_MS after the input until a figure painted, a view does not render,
  // so the figure's paint never waits for a software render. A dear render (over CHEAP_MS) waits
  // the whole INPUT_HOLD_MS after the last input: in a drag the next key comes 16-33 ms after a
  // paint, and a render started in that gap holds it back. A view waits at most MAX_WAIT_MS.
  //
  // The loop runs only while it has work: a view on screen with an animation playing or a
  // render due. meshcat's own loop asks for every animation frame for as long as the page lives,
  // and that alone, rendering nothing (a view scrolled away), cost headless Chromium a quarter
  // of a core per view page. A change wakes it: a command, anything that marks the view dirty
  // (meshcat's camera controls, its animation's progress), an animation played from its
  // controls, the view coming on screen.
  const FRAME_MS = 1000 / 60, INPUT_HOLD_MS = 150, MAX_WAIT_MS = 400, RENDER_WAIT = 3;
  const CHEAP_MS = FRAME_MS / 3;
  const frames = afmFrames();
  let visible = true, last = -Infinity, cost = 0, measuring = false, looping = false;
  // a task after the current one (posted from an animation frame: after its rendering update)
  const after = new MessageChannel();
  let start = 0;
  after.port1.onmessage = () => {
    const end = performance.now();
    cost = 0.6 * cost + 0.4 * (end - start);
    last = end;
    measuring = false;
  };
  const step = () => {
    if (!running) { looping = false; return; }
    const now = performance.now();
    const due = visible && (viewer.needs_render || viewer.animator.playing) && !measuring;
    if (due && now - last >= RENDER_WAIT * cost - FRAME_MS) {
      const held = now - frames.inputAt < INPUT_HOLD_MS
        && (frames.paintedAt < frames.inputAt || cost > CHEAP_MS);
      if (!(frames.pending > 0 || held) || now - last >= MAX_WAIT_MS) {
        start = now;
        // the animation advances only in a frame that renders it (its clock keeps its time):
        // meshcat's update also redraws its time control, a layout and paint of the page
        viewer.animator.update();
        if (viewer.needs_render) {
          viewer.render();
          measuring = true;
          after.port2.postMessage(null);
        }
      }
    }
    looping = visible && (viewer.needs_render || viewer.animator.playing || measuring);
    if (looping) requestAnimationFrame(step);
  };
  const wake = () => {
    if (looping || !running) return;
    looping = true;
    requestAnimationFrame(step);
  };
  const setDirty = viewer.set_dirty.bind(viewer);
  viewer.set_dirty = () => { setDirty(); wake(); };
  const play = viewer.animator.play.bind(viewer.animator);
  viewer.animator.play = () => { play(); wake(); };
  viewer.animate = wake; // meshcat's constructor queued one call of it
  const seen = typeof IntersectionObserver === "function"
    ? new IntersectionObserver((entries) => {
      visible = entries[entries.length - 1].isIntersecting;
      if (visible) viewer.set_dirty();
    }) : null;
  if (seen) seen.observe(host);
  return {
    viewer,
    apply(bytes) { if (running) { viewer.handle_command_bytearray(afmBytes(bytes)); wake(); } },
    setLegend(html) {
      legend.innerHTML = html || "";
      legend.style.display = html ? "" : "none";
    },
    setLabels(list) {
      labels.textContent = "";
      pins = (list || []).map((item) => {
        const el = document.createElement("div");
        el.className = "afm-scene-label";
        el.textContent = item.text;
        labels.appendChild(el);
        return { el, at: item.at };
      });
      viewer.set_dirty();
    },
    dispose() {
      running = false; // ends the requestAnimationFrame loop at its next frame
      if (observer) observer.disconnect();
      if (seen) seen.disconnect();
      after.port1.close(); // the render timer's channel: an open port keeps the view alive
      try { if (viewer.gui) viewer.gui.destroy(); } catch (e) { /* already gone */ }
      try { viewer.renderer.dispose(); viewer.renderer.forceContextLoss(); } catch (e) { /* */ }
      host.textContent = "";
    },
  };
}
