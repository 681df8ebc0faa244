// The static page of a 3D view (SceneView.static_html): the scene's commands embedded as base64.
function drawStatic(host, commands, legend, labels) {
  const view = afmCreateViewer(MeshCat, host);
  for (const c of commands) {
    const raw = atob(c), bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
    view.apply(bytes);
  }
  view.setLegend(legend);
  view.setLabels(labels);
  host.afmView = view; // for the browser tests
  return view;
}
