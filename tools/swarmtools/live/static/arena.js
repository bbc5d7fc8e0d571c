// arena.js - draws the arena on a canvas as the simulator's PNG frames do
// (sim_host/core/render.c: the same palette and the same order: walls,
// the tasks' floor shapes, obstacles and items, lamps, robots, then the
// shapes over everything); a robot's body has its colour of the legend
// (keys.js).
"use strict";

const Arena = (() => {
  const C = {                 // render.h's palette
    background: "#ffffff", floor: "#eeebe0", wall: "#3c3c46", outline: "#28282d",
    light: "#ffc814", lightRim: "#b4641e", heading: "#1e1e28", ledRed: "#ff1010", ledGreen: "#10e610",
  };
  const MARGIN = 12;          // px around the walls
  const MIN_ROBOT_PX = 4;     // a robot's radius is never drawn smaller
  const DETAIL_PX = 6;        // below this radius a robot is its body and heading only (no LEDs, no id):
                              // 2,000 robots' ids cost more than the rest of the frame (tools/bench/live_page.py)
  const LED_BODY = 8, LED_FRONT = 9;   // robot_state_t.leds bits

  const hex = Keys.hex;
  const finite = (...v) => v.every((x) => typeof x === "number" && Number.isFinite(x));

  // World (m, +y up, origin at the arena's centre) to canvas pixels, for the
  // arena of the scene (else RUN_INFO's), or around the robots' poses when
  // neither came (real robots with a tracker), zoomed by zoom.k about the
  // centre and panned by (zoom.px, zoom.py) pixels.  null: nothing to place.
  function layout(canvas, model, posed, zoom) {
    let w, h, wall = 0, cx0 = 0, cy0 = 0;
    const arena = model.scene ? model.scene.arena : model.info ? model.info.arena : null;
    if (arena && finite(arena[0], arena[1]) && arena[0] > 0 && arena[1] > 0) {
      [w, h] = arena;
      wall = model.scene && finite(model.scene.wall) ? model.scene.wall : 0;
    } else if (posed.length) {
      const xs = posed.map((r) => r.x), ys = posed.map((r) => r.y);
      const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
      w = Math.max(x1 - x0, 0.5) + 0.4;
      h = Math.max(y1 - y0, 0.5) + 0.4;
      cx0 = (x0 + x1) / 2;
      cy0 = (y0 + y1) / 2;
    } else {
      return null;
    }
    const z = zoom || { k: 1, px: 0, py: 0 };
    const s = z.k * Math.min((canvas.width - 2 * MARGIN) / (w + 2 * wall), (canvas.height - 2 * MARGIN) / (h + 2 * wall));
    const cx = canvas.width / 2 + z.px, cy = canvas.height / 2 + z.py;
    return {
      s, w, h, wall, walls: !!arena,
      toCanvas: (x, y) => [cx + (x - cx0) * s, cy - (y - cy0) * s],
      toWorld: (u, v) => [cx0 + (u - cx) / s, cy0 - (v - cy) / s],
    };
  }

  function disc(ctx, x, y, r, fill) {
    ctx.fillStyle = fill;
    ctx.beginPath();
    ctx.arc(x, y, Math.max(r, 0.5), 0, 2 * Math.PI);
    ctx.fill();
  }

  function star(ctx, x, y, r, fill) {
    ctx.fillStyle = fill;
    ctx.beginPath();
    for (let k = 0; k < 10; k++) {
      const a = -Math.PI / 2 + (k * Math.PI) / 5, rr = k % 2 ? r * 0.45 : r;
      ctx.lineTo(x + rr * Math.cos(a), y + rr * Math.sin(a));
    }
    ctx.closePath();
    ctx.fill();
  }

  function shape(ctx, L, d) {
    if (!finite(d.x, d.y)) return;
    const [x, y] = L.toCanvas(d.x, d.y), colour = hex(d.rgb);
    ctx.fillStyle = ctx.strokeStyle = colour;
    ctx.lineWidth = Math.max(finite(d.line) ? d.line * L.s : 0, 1);
    switch (d.kind) {
      case 0:   // disc
        if (finite(d.radius) && d.radius > 0) disc(ctx, x, y, Math.max(d.radius * L.s, 1), colour);
        break;
      case 1:   // ring
        if (finite(d.radius) && d.radius > 0) {
          ctx.beginPath();
          ctx.arc(x, y, d.radius * L.s, 0, 2 * Math.PI);
          ctx.stroke();
        }
        break;
      case 2:   // rectangle
        if (finite(d.w, d.h)) ctx.fillRect(x - (d.w * L.s) / 2, y - (d.h * L.s) / 2, d.w * L.s, d.h * L.s);
        break;
      case 3: { // line
        if (!finite(d.x2, d.y2)) break;
        const [x2, y2] = L.toCanvas(d.x2, d.y2);
        ctx.beginPath();
        ctx.moveTo(x, y);
        ctx.lineTo(x2, y2);
        ctx.stroke();
        break;
      }
      case 4:   // label: (x, y) is its lower left corner
        ctx.font = "bold 12px sans-serif";
        ctx.textBaseline = "bottom";
        ctx.fillText(d.text, x, y);
        break;
      default:
        break;
    }
  }

  function obstacle(ctx, L, o) {
    if (!finite(o.x, o.y)) return;
    const [x, y] = L.toCanvas(o.x, o.y);
    if (o.shape === 0 && finite(o.radius)) {
      const r = Math.max(o.radius * L.s, 1);
      disc(ctx, x, y, r, C.outline);
      disc(ctx, x, y, r > 3 ? r - 1 : r, hex(o.rgb));
    } else if (o.shape === 1 && finite(o.width, o.depth, o.angle)) {
      ctx.save();
      ctx.translate(x, y);
      ctx.rotate((-o.angle * Math.PI) / 180);
      const hx = Math.max((o.width * L.s) / 2, 0.5), hy = Math.max((o.depth * L.s) / 2, 0.5);
      ctx.fillStyle = C.outline;
      ctx.fillRect(-hx, -hy, 2 * hx, 2 * hy);
      ctx.fillStyle = hex(o.rgb);
      if (hx > 3 && hy > 3) ctx.fillRect(-hx + 1, -hy + 1, 2 * hx - 2, 2 * hy - 2);
      ctx.restore();
    }
  }

  // One robot: rim, body in its colour, body LED, heading bar, front LED,
  // ring LEDs (LED i at -45*i degrees from the heading), id.  Returns where
  // it went.
  function robot(ctx, L, rb, r, fill) {
    const [x, y] = L.toCanvas(rb.x, rb.y);
    const th = finite(rb.theta) ? rb.theta : 0;
    const c = Math.cos(th), s = -Math.sin(th);     // canvas y points down
    const rim = Math.max(1, 0.08 * r);
    disc(ctx, x, y, r, C.outline);
    disc(ctx, x, y, r - rim, fill);
    if (r < DETAIL_PX) {
      ctx.strokeStyle = C.heading;
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.lineTo(x + r * c, y + r * s);
      ctx.stroke();
      return { id: rb.id, x, y };
    }
    if (rb.leds & (1 << LED_BODY)) disc(ctx, x, y, Math.max(0.3 * r, 1), C.ledGreen);
    ctx.strokeStyle = C.heading;
    ctx.lineWidth = Math.max(1.2, 0.18 * r);
    ctx.beginPath();
    ctx.moveTo(x, y);
    ctx.lineTo(x + (r - rim) * c, y + (r - rim) * s);
    ctx.stroke();
    if (rb.leds & (1 << LED_FRONT)) disc(ctx, x + 0.55 * r * c, y + 0.55 * r * s, Math.max(0.7, 0.13 * r), C.ledRed);
    const lr = Math.max(0.7, 0.16 * r), ld = r - rim - 0.5 * lr;
    for (let i = 0; i < 8; i++) {
      if (!(rb.leds & (1 << i))) continue;
      const a = th - (i * Math.PI) / 4;
      disc(ctx, x + ld * Math.cos(a), y - ld * Math.sin(a), lr, C.ledRed);
    }
    ctx.fillStyle = C.heading;
    ctx.font = "10px sans-serif";
    ctx.textBaseline = "bottom";
    ctx.fillText(String(rb.id), x + 0.8 * r, y - 0.8 * r);
    return { id: rb.id, x, y };
  }

  // What the selected robot perceives (its robot_detail_t, when the run
  // sends it): its IR range, its camera's field of view and blobs, lines to
  // where the IR messages waiting in its inbox came from.
  function perception(ctx, L, rb, d, r) {
    const [x, y] = L.toCanvas(rb.x, rb.y);
    const th = finite(rb.theta) ? rb.theta : 0;
    ctx.strokeStyle = "#d62728";
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(x, y, r + 4, 0, 2 * Math.PI);
    ctx.stroke();
    if (!d || d.id !== rb.id) return;
    if (finite(d.ircom_range_m) && d.ircom_range_m > 0) {
      ctx.setLineDash([4, 4]);
      ctx.strokeStyle = "#9467bd";
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.arc(x, y, d.ircom_range_m * L.s, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
    }
    if (finite(d.camera_fov_rad, d.camera_range_m) && d.camera_fov_rad > 0 && d.camera_range_m > 0) {
      const R = d.camera_range_m * L.s, half = Math.min(d.camera_fov_rad, 2 * Math.PI) / 2;
      ctx.fillStyle = "rgba(31, 119, 180, 0.12)";
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.arc(x, y, R, -th - half, -th + half);
      ctx.closePath();
      ctx.fill();
      ctx.strokeStyle = "#1f77b4";
      for (const b of d.blobs) {
        const a = th + b.bearing_mrad / 1000;
        ctx.beginPath();
        ctx.moveTo(x, y);
        ctx.lineTo(x + R * Math.cos(a), y - R * Math.sin(a));
        ctx.stroke();
      }
    }
    ctx.strokeStyle = "#9467bd";
    for (const h of d.heard) {
      const a = th + h.bearing_mrad / 1000, R = (h.range_mm / 1000) * L.s;
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.lineTo(x + R * Math.cos(a), y - R * Math.sin(a));
      ctx.stroke();
    }
  }

  // A scale bar in the lower left corner: a round length near 100 px.
  function scaleBar(ctx, canvas, L) {
    const want = 100 / L.s, p = 10 ** Math.floor(Math.log10(want));
    const m = [1, 2, 5, 10].map((k) => k * p).filter((v) => v <= want).pop() || p;
    const px = m * L.s, x0 = 12, y0 = canvas.height - 12;
    ctx.fillStyle = "rgba(255, 255, 255, 0.8)";        // readable over the wall or the floor
    ctx.fillRect(x0 - 4, y0 - 18, px + 8, 22);
    ctx.strokeStyle = ctx.fillStyle = "#222";
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x0 + px, y0);
    ctx.stroke();
    ctx.font = "11px sans-serif";
    ctx.textBaseline = "bottom";
    ctx.fillText(m >= 1 ? `${m} m` : `${Math.round(m * 1000)} mm`, x0, y0 - 3);
    return m;
  }

  // Draws everything; returns the layout (null: nothing to place) and
  // where each robot went.  `bodyOf(robot)`: its body's colour; `zoom` as
  // layout's; `selected`: a robot id whose perception (`detail`) is drawn,
  // or null.
  function draw(canvas, model, robots, bodyOf, zoom, selected, detail) {
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = C.background;
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    const posed = robots.filter((r) => r.pose && finite(r.x, r.y));
    const L = layout(canvas, model, posed, zoom);
    if (!L) return { layout: null, drawn: [], radius: 0 };
    if (L.walls) {
      const wall = Math.max(L.wall * L.s, 2);
      const [x0, y0] = L.toCanvas(-L.w / 2, L.h / 2);
      ctx.fillStyle = C.wall;
      ctx.fillRect(x0 - wall, y0 - wall, L.w * L.s + 2 * wall, L.h * L.s + 2 * wall);
      ctx.fillStyle = C.floor;
      ctx.fillRect(x0, y0, L.w * L.s, L.h * L.s);
    }
    const shapes = model.drawing ? model.drawing.shapes : [];
    shapes.filter((d) => d.layer === 0).forEach((d) => shape(ctx, L, d));
    if (model.scene) model.scene.obstacles.forEach((o) => obstacle(ctx, L, o));
    if (model.drawing) {
      model.drawing.items.forEach(([x, y, r, rgb]) => obstacle(ctx, L, { shape: 0, x, y, radius: r, rgb }));
    }
    if (model.scene) {
      const lr = Math.max(0.05 * L.s, 7);
      model.scene.lights.forEach((l) => {
        if (!finite(l.x, l.y)) return;
        const [x, y] = L.toCanvas(l.x, l.y);
        star(ctx, x, y, lr + 2, C.lightRim);
        star(ctx, x, y, lr, C.light);
      });
    }
    const radius = model.scene && finite(model.scene.robot_radius) ? model.scene.robot_radius : 0.035;
    const r = Math.max(radius * L.s, MIN_ROBOT_PX);
    const drawn = posed.map((rb) => robot(ctx, L, rb, r, bodyOf(rb)));
    shapes.filter((d) => d.layer !== 0).forEach((d) => shape(ctx, L, d));
    const sel = selected === null ? null : posed.find((rb) => rb.id === selected);
    if (sel) perception(ctx, L, sel, detail, r);
    const scale = scaleBar(ctx, canvas, L);
    return { layout: L, drawn, radius: r, scale };
  }

  return { draw, hex, layout };
})();
