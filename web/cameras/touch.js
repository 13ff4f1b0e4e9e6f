// Touch gestures on the orbit camera: one finger orbits, two fingers pinch to zoom and move
// together to pan. (In the fly and walk cameras one finger looks around.) Pointer events,
// so a pen or a mouse never lands here: the mouse has its own handler in rig.js.
export function attachTouchControls(element, rig) {
  const touches = new Map(); // pointerId -> {x, y}
  let last = null;           // the previous centroid and spread of the touches

  const gesture = () => {
    const points = [...touches.values()];
    const x = points.reduce((s, p) => s + p.x, 0) / points.length;
    const y = points.reduce((s, p) => s + p.y, 0) / points.length;
    const spread = points.length > 1 ? Math.hypot(points[0].x - points[1].x, points[0].y - points[1].y) : 0;
    return { x, y, spread, count: points.length };
  };

  element.addEventListener('pointerdown', (e) => {
    if (e.pointerType !== 'touch') return;
    touches.set(e.pointerId, { x: e.clientX, y: e.clientY });
    try { element.setPointerCapture(e.pointerId); } catch { /* a synthetic or finished pointer */ }
    last = gesture();
  });
  element.addEventListener('pointermove', (e) => {
    if (e.pointerType !== 'touch' || !touches.has(e.pointerId)) return;
    touches.set(e.pointerId, { x: e.clientX, y: e.clientY });
    const now = gesture();
    if (last && now.count === last.count) {
      const dx = now.x - last.x, dy = now.y - last.y;
      const camera = rig.active;
      if (camera.mode !== 'orbit') camera.look(dx, dy);
      else if (now.count === 1) camera.drag(dx, dy, false);
      else {
        if (last.spread > 0 && now.spread > 0) camera.zoom(last.spread / now.spread);
        camera.drag(dx, dy, true);
      }
      rig.changed();
    }
    last = now;
  });
  const end = (e) => {
    if (e.pointerType !== 'touch') return;
    touches.delete(e.pointerId);
    last = touches.size ? gesture() : null;
  };
  element.addEventListener('pointerup', end);
  element.addEventListener('pointercancel', end);
}
