// live.js - the page's state and its WebSocket to swarm-live: frames from
// the server (view.py's View.frame: the parts that changed) update `model`,
// which is drawn at once; the controls send play, pause, step, speed and
// seek (to a run under swarmsim --control: pause, resume, step, its
// real-time factor).  Click a robot to inspect it (select), drag it to move
// it (a run under control); the wheel zooms, dragging the floor pans, a
// double click shows the whole arena again.
// What the page shows is published as window.liveState (for tests and
// scripts), and window.liveView.toCanvas(x, y) maps metres to canvas pixels.
"use strict";

(() => {
  const bodyOf = (rb) => Keys.body(model, rb);    // a robot's colour (keys.js)
  const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 5, 10, 20, 50, 100, 1000];
  const PARTS = ["info", "schemas", "scene", "drawing", "swarm", "summary", "bridge", "events", "error", "limits",
                 "control", "detail"];
  const CHART_EVERY_MS = 250;   // charts are redrawn at most this often (the arena every frame)

  const $ = (id) => document.getElementById(id);
  const canvas = $("arena"), playButton = $("play"), speedSelect = $("speed"), seek = $("seek");
  const model = {
    mode: null, source: "", time: 0, clock: null, end: null, playing: false, speed: 1, ended: false,
    robots: new Map(), series: { t: [], cols: {}, units: {} },
  };
  let ws = null, connected = false, frames = 0, seeking = false, chartsAt = 0, chartTimer = null, chartKeys = [], chartAxes = {};
  let drawn = { layout: null, drawn: [], radius: 0 };
  const zoom = { k: 1, px: 0, py: 0 };
  let selected = null, press = null, answered = null, legend = [];

  function clear() {
    for (const p of PARTS) model[p] = null;
    model.robots.clear();
    model.series = { t: [], cols: {}, units: {} };
  }
  clear();

  function send(cmd) {
    if (ws && ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(cmd));
  }

  function addSeries(s, whole) {
    if (whole) {
      model.series = { t: s.t.slice(), cols: {}, units: Object.assign({}, s.units) };
      for (const [k, v] of Object.entries(s.cols)) model.series.cols[k] = v.slice();
      return;
    }
    const n = model.series.t.length;
    for (const [name, v] of Object.entries(s.cols)) {
      if (!(name in model.series.cols)) model.series.cols[name] = new Array(n).fill(null);
      model.series.cols[name].push(...v);
    }
    model.series.t.push(...s.t);
    Object.assign(model.series.units, s.units);
  }

  function showError(text, sticky) {
    const box = $("error");
    box.textContent = text;
    box.hidden = !text;
    if (text && !sticky) setTimeout(() => { if (box.textContent === text) box.hidden = true; }, 5000);
  }

  function controls() {
    const live = model.mode === "live", steered = live && !!model.control;
    playButton.disabled = !connected;
    playButton.textContent = steered ? (model.control.paused ? "resume" : "pause")
      : live ? (model.playing ? "freeze" : "follow")
      : model.playing ? "pause" : model.ended ? "replay" : "play";
    $("step").disabled = !connected || (live && !steered);
    $("step").hidden = $("step-n").hidden = live && !steered;
    $("speed-label").hidden = live && !steered;
    if (steered) {
      const rt = model.control.realtime;
      if (![...speedSelect.options].some((o) => Number(o.value) === rt)) speedSelect.append(new Option(`${rt}x`, String(rt)));
      if (document.activeElement !== speedSelect) speedSelect.value = String(rt);
    }
    seek.hidden = live;
    if (!live && model.end !== null) {
      seek.max = String(model.end);
      if (!seeking) seek.value = String(model.time);
      if (!SPEEDS.includes(model.speed) && ![...speedSelect.options].some((o) => Number(o.value) === model.speed)) {
        speedSelect.append(new Option(`${model.speed}x`, String(model.speed)));
      }
      speedSelect.value = String(model.speed);
    }
  }

  function render(chartsNow) {
    // The selected robot as of its latest details (every step), when newer
    // than its state (the robot rate): where a drag put it, at once.
    const d = model.detail;
    const robots = [...model.robots.values()].sort((a, b) => a.id - b.id).map((r) => (
      d && r.id === d.id && r.id === selected && d.clock >= r.clock
        ? Object.assign({}, r, { x: d.x, y: d.y, theta: d.theta, state: d.state, leds: d.leds, pose: true }) : r));
    const followed = $("follow").checked && selected !== null ? robots.find((r) => r.id === selected) : null;
    if (followed && followed.pose && Number.isFinite(followed.x) && Number.isFinite(followed.y)) {
      const L0 = Arena.layout(canvas, model, robots.filter((r) => r.pose), { k: zoom.k, px: 0, py: 0 });
      if (L0) {
        const [u, v] = L0.toCanvas(followed.x, followed.y);
        zoom.px = canvas.width / 2 - u;
        zoom.py = canvas.height / 2 - v;
      }
    }
    drawn = Arena.draw(canvas, model, robots, bodyOf, zoom, selected, model.detail);
    if (press && press.robot !== null && press.moved && drawn.layout) {   // where a dragged robot would go
      const ctx = canvas.getContext("2d");
      ctx.strokeStyle = "#d62728";
      ctx.setLineDash([3, 3]);
      ctx.beginPath();
      ctx.arc(press.u, press.v, drawn.radius, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
    }
    const placed = new Set(drawn.drawn.map((d) => d.id));
    const unplaced = robots.filter((r) => !placed.has(r.id));
    const nopos = $("nopos");
    canvas.hidden = !drawn.layout;
    nopos.hidden = !unplaced.length;
    nopos.textContent = drawn.layout
      ? `no positions for ${unplaced.length} of ${robots.length} robots (no pose known): shown as tiles`
      : "no positions: these robots publish no pose (pose_known 0, no tracker), so they are shown as tiles of their states";
    Panels.clock(model);
    Panels.run(model, robots);
    legend = Keys.entries(model, robots);
    Panels.legend(legend);
    Panels.tiles(model, unplaced, bodyOf);
    Panels.robotPanel(model, selected === null ? null : model.robots.get(selected), model.detail, bodyOf);
    Panels.paramsForm(selected !== null && model.detail && model.detail.id === selected ? model.detail : null,
      (robot, group, key, value) => send({ cmd: "set", robot, group, key, value }));
    const c = model.control;
    if (c && c.seq !== answered) {     // the run's answer to the latest command
      answered = c.seq;
      if (!c.ok && c.text) showError(`the simulation refused it: ${c.text}`, false);
    }
    Panels.summary(model);
    Panels.bridge(model);
    Panels.events(model);
    if (model.error) showError(model.error, true);
    $("limits").textContent = model.limits || "";      // what the server cut (swarmtools/live/limits.py)
    $("limits").hidden = !model.limits;
    const wait = CHART_EVERY_MS - (performance.now() - chartsAt);
    if (chartsNow || wait <= 0) {
      charts();
    } else if (!chartTimer) {
      chartTimer = setTimeout(charts, wait);   // the latest points are drawn even if no frame follows
    }
    controls();
    publish(robots, unplaced);
  }

  function charts() {
    clearTimeout(chartTimer);
    chartTimer = null;
    const drawnCharts = Charts.render($("charts"), model.series, Keys.stateColour);
    chartKeys = drawnCharts.keys;
    chartAxes = drawnCharts.axes;
    chartsAt = performance.now();
    if (window.liveState) Object.assign(window.liveState, { charts: chartKeys.slice(), chartAxes });
  }

  function publish(robots, unplaced) {
    const d = model.drawing, sc = model.scene;
    window.liveState = {
      connected, mode: model.mode, source: model.source, frames,
      time: model.time, clock: model.clock, end: model.end,
      playing: model.playing, speed: model.speed, ended: model.ended,
      scenario: model.info ? model.info.scenario : null, run: model.info ? model.info.run : null,
      step: model.swarm ? model.swarm.step : null,
      robots: robots.map((r) => ({ id: r.id, x: r.x, y: r.y, theta: r.theta, pose: r.pose, state: r.state,
                                   controller: r.controller, leds: r.leds })),
      placed: drawn.drawn, radiusPx: drawn.radius, tiles: unplaced.length, noPositions: !$("nopos").hidden,
      obstacles: sc ? sc.obstacles.length : 0, lights: sc ? sc.lights.length : 0,
      shapes: d ? d.shapes.length : 0, items: d ? d.items.length : 0,
      seriesPoints: model.series.t.length, charts: chartKeys.slice(), chartAxes,
      stateColours: Keys.stateColours(), legend: legend.map((e) => Object.assign({}, e)),
      bodies: Object.fromEntries(robots.map((r) => [r.id, bodyOf(r)])),
      summary: model.summary ? model.summary.state_hash : null,
      bridgeDevices: model.bridge ? model.bridge.devices.length : 0,
      selected, zoom: Object.assign({}, zoom), scaleM: drawn.scale || null,
      control: model.control ? Object.assign({}, model.control) : null,
      detail: model.detail ? { id: model.detail.id, clock: model.detail.clock, prox: model.detail.prox,
                               ambient: model.detail.ambient, blobs: model.detail.blobs.length,
                               heard: model.detail.heard.length, x: model.detail.x, y: model.detail.y,
                               state: model.detail.state, state_time_s: model.detail.state_time_s, values: model.detail.values, wheels: model.detail.wheels,
                               params: model.detail.params } : null,
      panel: $("robot").textContent,
      error: model.error, limits: model.limits,
    };
  }

  function onMessage(msg) {
    if (msg.type === "hello") {
      model.mode = msg.mode;
      model.source = msg.source;
      model.end = msg.end;
      model.speed = msg.speed;
      model.playing = msg.playing;
      $("source").textContent = msg.source;
      document.title = `swarm-live: ${msg.source}`;
    } else if (msg.type === "frame") {
      if (msg.reset) clear();
      for (const p of PARTS) if (p in msg) model[p] = msg[p];
      if (msg.robots) for (const r of msg.robots) model.robots.set(r.id, r);
      if (msg.series) addSeries(msg.series, msg.series_reset);
      Object.assign(model, { time: msg.time, clock: msg.clock, playing: msg.playing, speed: msg.speed,
                             ended: msg.ended, end: msg.end });
      frames++;
      render(!!msg.series_reset);
    } else if (msg.type === "error") {
      showError(msg.text, false);
    }
  }

  function connect() {
    const status = $("status");
    ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`);
    ws.onopen = () => {
      connected = true;
      status.textContent = "connected";
      status.classList.remove("bad");
    };
    ws.onmessage = (ev) => onMessage(JSON.parse(ev.data));
    ws.onclose = () => {
      connected = false;
      status.textContent = "disconnected: swarm-live stopped? (reload to reconnect)";
      status.classList.add("bad");
      controls();
      publish([...model.robots.values()], []);
    };
  }

  for (const s of SPEEDS) speedSelect.append(new Option(`${s}x`, String(s)));
  playButton.addEventListener("click", () => send({ cmd: model.playing ? "pause" : "play" }));
  speedSelect.addEventListener("change", () => send({ cmd: "speed", value: Number(speedSelect.value) }));
  seek.addEventListener("input", () => { seeking = true; });
  seek.addEventListener("change", () => {
    seeking = false;
    send({ cmd: "seek", value: Number(seek.value) });
  });
  $("step").addEventListener("click", () => {
    const n = Math.round(Number($("step-n").value));
    if (!(n >= 1)) { showError("step: the number of control steps is 1 or more", false); return; }
    send({ cmd: "step", value: n });
  });

  // The canvas: pixel coordinates of a mouse event (the canvas may be scaled by CSS).
  const at = (ev) => {
    const b = canvas.getBoundingClientRect();
    return [((ev.clientX - b.left) * canvas.width) / b.width, ((ev.clientY - b.top) * canvas.height) / b.height];
  };
  const robotAt = (u, v) => {
    let best = null, bestD = Math.max(drawn.radius, 6) + 3;
    for (const d of drawn.drawn) {
      const dist = Math.hypot(d.x - u, d.y - v);
      if (dist <= bestD) { best = d.id; bestD = dist; }
    }
    return best;
  };
  const redraw = () => render(false);
  canvas.addEventListener("mousedown", (ev) => {
    const [u, v] = at(ev);
    press = { u0: u, v0: v, u, v, robot: robotAt(u, v), moved: false, px: zoom.px, py: zoom.py };
  });
  canvas.addEventListener("mousemove", (ev) => {
    if (!press) return;
    const [u, v] = at(ev);
    press.u = u;
    press.v = v;
    press.moved = press.moved || Math.hypot(u - press.u0, v - press.v0) > 3;
    if (press.robot === null && press.moved) {    // pan
      zoom.px = press.px + (u - press.u0);
      zoom.py = press.py + (v - press.v0);
    }
    if (press.moved) redraw();
  });
  window.addEventListener("mouseup", () => {
    const p = press;
    press = null;
    if (!p) return;
    if (!p.moved) {                              // a click: inspect that robot (or none)
      selected = p.robot;
      if (model.mode === "live" && model.control) send({ cmd: "select", robot: selected === null ? -1 : selected });
    } else if (p.robot !== null && drawn.layout) {   // a drag: move it there
      if (model.mode === "live" && model.control) {
        const [x, y] = drawn.layout.toWorld(p.u, p.v), rb = model.robots.get(p.robot);
        send({ cmd: "move", robot: p.robot, x, y, theta: rb && Number.isFinite(rb.theta) ? rb.theta : 0 });
      } else {
        showError("moving a robot needs a run under swarmsim --control (a log or a plain live run cannot be changed)", false);
      }
    }
    redraw();
  });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    const [u, v] = at(ev), k = Math.min(Math.max(zoom.k * Math.exp(-ev.deltaY / 500), 0.25), 200);
    const cx = canvas.width / 2, cy = canvas.height / 2;    // keep the point under the cursor where it is
    zoom.px = u - cx - ((u - cx - zoom.px) * k) / zoom.k;
    zoom.py = v - cy - ((v - cy - zoom.py) * k) / zoom.k;
    zoom.k = k;
    redraw();
  }, { passive: false });
  $("follow").addEventListener("change", redraw);
  canvas.addEventListener("dblclick", () => { Object.assign(zoom, { k: 1, px: 0, py: 0 }); redraw(); });

  window.liveView = {
    toCanvas: (x, y) => (drawn.layout ? drawn.layout.toCanvas(x, y) : null),
    toWorld: (u, v) => (drawn.layout ? drawn.layout.toWorld(u, v) : null),
  };
  publish([], []);
  connect();
})();
