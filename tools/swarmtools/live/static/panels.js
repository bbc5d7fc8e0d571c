// panels.js - the page's text: the clock, what runs, the legend (keys.js),
// tiles for robots without a position, the run's summary, the
// bridge's counters and the latest events.  Built with DOM nodes and
// textContent: names come from the telemetry and are never HTML.
"use strict";

const Panels = (() => {
  function el(tag, props, ...children) {
    const e = document.createElement(tag);
    Object.assign(e, props || {});
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  function fill(id, ...children) {
    const box = document.getElementById(id);
    box.replaceChildren(...children);
    return box;
  }

  // kind: drawing.h's draw_key_kind_t (0 a robot, 1 an area, 2 an outline,
  // 3 an item, 4 a line): the swatch looks like what it stands for.
  const SWATCH = ["robot", "area", "ring", "item", "line"];
  function swatch(colour, kind) {
    const s = el("span", { className: `swatch ${SWATCH[kind] || "robot"}` });
    if (kind === 2) s.style.borderColor = colour; else s.style.background = colour;
    return s;
  }

  function clock(model) {
    const parts = [];
    if (model.clock !== null && model.clock !== undefined) {
      parts.push(`t = ${model.clock.toFixed(1)} s`);
      const sw = model.swarm, steps = model.info ? model.info.steps : 0;
      const step = model.control ? model.control.step : sw ? sw.step : null;
      if (step !== null) parts.push(`step ${step}${steps ? ` of ${steps} (${Math.round((100 * step) / steps)} %)` : ""}`);
      if (model.control) {
        const c = model.control;
        parts.push(c.paused ? "PAUSED" : `${Charts.fmt(c.realtime)}x real time`);
        if (c.pending) parts.push(`${c.pending} steps to go`);
      }
    } else {
      const since = model.mode === "log" ? "since the log's first message" : "since swarm-live started";
      parts.push(`t = ${model.time.toFixed(1)} s ${since}`);
    }
    if (model.mode === "log" && model.end !== null) parts.push(`log ${model.time.toFixed(1)} / ${model.end.toFixed(1)} s`);
    document.getElementById("clock").textContent = parts.join("   ");
  }

  function run(model, robots) {
    const i = model.info, out = [];
    if (i) {
      out.push(el("h2", { textContent: `${i.scenario} (seed ${i.run})` }));
      const groups = i.groups.map((g) => `${g.name}: ${g.count} x ${g.controller}${g.policy ? "/" + g.policy : ""}`);
      out.push(el("div", { textContent: `${i.robots} robots, ${i.arena[0]} x ${i.arena[1]} m, ${i.period_ms} ms steps` }));
      out.push(el("div", { textContent: `groups: ${groups.join(", ")}` }));
      out.push(el("div", { textContent: `tasks: ${i.tasks.length ? i.tasks.join(", ") : "none"}` }));
    } else if (robots.length) {
      out.push(el("h2", { textContent: `${robots.length} robots heard (no RUN_INFO: real robots)` }));
    } else {
      out.push(el("h2", { textContent: "waiting for messages ..." }));
    }
    fill("run", ...out);
  }

  // The legend: Keys.entries's, a robot key with its count.
  function legend(entries) {
    fill("legend", ...entries.map((e) => el("span", { className: "key" }, swatch(e.colour, e.kind),
      e.count === null ? e.label : `${e.label} ${e.count}`)));
  }

  function valueLines(model, rb) {
    const ctrl = model.schemas && model.schemas.controller ? model.schemas.controller[rb.controller] : null;
    return rb.values.map((v, k) => {
      const name = ctrl && k < ctrl.names.length ? ctrl.names[k] : `value${k}`;
      const unit = ctrl && k < ctrl.units.length && ctrl.units[k] ? " " + ctrl.units[k] : "";
      return el("div", { textContent: `${name} ${Charts.fmt(v)}${unit}` });
    });
  }

  // A tile per robot the arena cannot place.
  function tiles(model, unplaced, bodyOf) {
    const box = fill("tiles", ...unplaced.map((rb) => {
      const age = model.time - rb.seen;
      const state = el("span", { className: "state", textContent: rb.state });
      state.style.background = bodyOf(rb);
      const leds = [];
      for (let i = 0; i < 10; i++) if (rb.leds & (1 << i)) leds.push(i < 8 ? `${i}` : i === 8 ? "body" : "front");
      return el("div", { className: "tile" + (age > 5 ? " stale" : "") },
        el("div", {}, el("b", { textContent: `robot ${rb.id} ` }), `${rb.controller} `, state),
        el("div", { className: "values" }, ...valueLines(model, rb)),
        el("div", { className: "values", textContent: `wheels ${rb.wheels[0]}/${rb.wheels[1]}  leds ${leds.join(",") || "-"}` }),
        el("div", { className: "values", textContent: `seen ${age.toFixed(1)} s ago` }));
    }));
    box.dataset.count = String(unplaced.length);
  }

  // IR proximity (outwards: nearer) and ambient (inwards: brighter) per
  // sensor, on a small polar plot with the robot's heading up.
  function polar(detail) {
    const cv = el("canvas", { width: 150, height: 150, className: "polar" });
    const ctx = cv.getContext("2d"), c = 75, R = 62;
    ctx.strokeStyle = "#bbb";
    ctx.beginPath();
    ctx.arc(c, c, R, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(c, c);
    ctx.lineTo(c, c - R - 8);
    ctx.stroke();
    const ray = (k, frac, colour, w) => {
      const a = detail.ir_bearing_mrad[k] / 1000 + Math.PI / 2;   // ahead is up
      ctx.strokeStyle = colour;
      ctx.lineWidth = w;
      ctx.beginPath();
      ctx.moveTo(c, c);
      ctx.lineTo(c + R * frac * Math.cos(a), c - R * frac * Math.sin(a));
      ctx.stroke();
    };
    for (let k = 0; k < 8; k++) {
      if (detail.ambient) ray(k, 1 - Math.min(detail.ambient[k], 4095) / 4095, "#edc948", 6);
      if (detail.prox) ray(k, Math.min(detail.prox[k], 4095) / 4095, "#e15759", 3);
    }
    return cv;
  }

  // The selected robot: its state and values (robot_state_t), and, from a
  // run under control, its latest readings (robot_detail_t).
  function robotPanel(model, rb, detail, bodyOf) {
    if (!rb) { fill("robot"); return; }
    const d = detail && detail.id === rb.id ? detail : null;
    const src = d || rb;
    const state = el("span", { className: "state", textContent: src.state });
    state.style.background = bodyOf(src);
    const leds = [];
    for (let i = 0; i < 10; i++) if (src.leds & (1 << i)) leds.push(i < 8 ? `${i}` : i === 8 ? "body" : "front");
    const deg = (rad) => `${Math.round((rad * 180) / Math.PI)}°`;
    const out = [
      el("h2", {}, `robot ${rb.id} `, el("span", { textContent: `${src.controller} ` }), state,
        d && d.state_time_s != null ? el("span", { className: "state-time", textContent: ` for ${Charts.fmt(d.state_time_s)} s` }) : null),
      el("div", { className: "values" }, ...valueLines(model, { controller: src.controller, values: src.values })),
      el("div", { className: "values", textContent:
        `pose ${rb.pose || d ? `(${Charts.fmt(src.x)}, ${Charts.fmt(src.y)}) m, ${deg(src.theta)}` : "unknown"}` }),
      el("div", { className: "values", textContent: `wheels ${src.wheels[0]} / ${src.wheels[1]} steps/s   LEDs ${leds.join(",") || "-"}` }),
    ];
    if (d) {
      out.push(el("div", { className: "values", textContent:
        `IR prox ${d.prox ? d.prox.join(" ") : "not read"}   ambient ${d.ambient ? d.ambient.join(" ") : "not read"}` }));
      if (d.prox || d.ambient) out.push(polar(d));
      out.push(el("div", { className: "values", textContent: d.blobs.length
        ? `blobs: ${d.blobs.map((b) => `colour ${b.colour} at ${deg(b.bearing_mrad / 1000)} (${deg(b.width_mrad / 1000)} wide)`).join("; ")}`
        : "blobs: none" }));
      if (d.mic.length) out.push(el("div", { className: "values", textContent: `microphone per band: ${d.mic.map(Charts.fmt).join(" / ")} counts` }));
      out.push(el("div", { className: "values", textContent: d.heard.length
        ? `IR messages waiting: ${d.heard.map((h) => `${h.value} from ${deg(h.bearing_mrad / 1000)} at ${h.range_mm} mm`).join("; ")}`
        : "IR messages waiting: none" }));
    } else {
      out.push(el("div", { className: "values", textContent:
        `IR max ${rb.ir_max}   ambient min ${rb.ambient_min}   blobs ${rb.blobs}   (a run under --control sends every reading)` }));
    }
    fill("robot", ...out);
  }

  // The selected robot's live keys (robot_detail_t: those its controller
  // lets a run under control set while it goes), each with a box for a new
  // value.  The form is built again only for another robot or other keys,
  // so that what is being typed stays; the values shown follow the run.
  let paramsFor = null;
  function paramsForm(detail, onSet) {
    const form = document.getElementById("robot-params");
    const keys = detail && detail.params ? detail.params : [];
    const id = detail ? `${detail.id}:${detail.group}:${keys.map((p) => p.name).join(",")}` : null;
    form.hidden = !detail || !keys.length;
    if (form.hidden) { paramsFor = null; form.replaceChildren(); return; }
    if (id !== paramsFor) {
      paramsFor = id;
      const group = el("input", { type: "checkbox", id: "param-group" });
      form.replaceChildren(
        el("h2", { textContent: "parameters (set while the run goes)" }),
        ...keys.map((p) => {
          const input = el("input", { type: "text", id: `param-${p.name}`, placeholder: p.value,
                                      title: `a new value in ${p.range}` });
          const button = el("button", { type: "button", id: `set-${p.name}`, textContent: "set" });
          button.addEventListener("click", () => onSet(detail.id, group.checked, p.name, input.value.trim()));
          input.addEventListener("keydown", (e) => { if (e.key === "Enter") { e.preventDefault(); button.click(); } });
          return el("div", { className: "row" }, el("span", { className: "key", textContent: p.name }),
            el("span", { className: "now", id: `now-${p.name}` }), input, button,
            el("span", { className: "range", textContent: p.range }));
        }),
        el("label", { className: "row" }, group, `every robot of group ${detail.group}`));
    }
    for (const p of keys) document.getElementById(`now-${p.name}`).textContent = p.value;
  }

  function summary(model) {
    const m = model.summary;
    if (!m) { fill("summary"); return; }
    fill("summary", el("h2", { textContent: `run finished after ${m.steps} steps (state ${m.state_hash})` }),
      el("div", { textContent: m.metrics.map(([n, v]) => `${n} ${Charts.fmt(v)}`).join("   ") }));
  }

  function bridge(model) {
    const b = model.bridge;
    if (!b) { fill("bridge"); return; }
    const head = el("tr", {}, ...["device", "robot", "link", "frames", "crc", "framing", "lost", "reconnects"]
      .map((h) => el("th", { textContent: h })));
    const rows = b.devices.map((d) => el("tr", {}, ...[d.device, d.robot_id, d.connected ? "up" : "DOWN", d.frames,
      d.crc_errors, d.framing_errors, d.lost, d.reconnects].map((v) => el("td", { textContent: String(v) }))));
    fill("bridge", el("h2", { textContent: "bridge" }), el("table", {}, head, ...rows));
  }

  function events(model) {
    const e = model.events;
    if (!e) { fill("events"); return; }
    const counts = Object.entries(e.counts).map(([k, n]) => `${k} ${n}`).join("   ");
    const latest = [...e.latest].reverse().map((ev) => el("li", {
      textContent: `${ev.clock.toFixed(1)} s  robot ${ev.robot}  ${ev.kind}${ev.value ? " " + ev.value : ""}${ev.detail ? " " + ev.detail : ""}`,
    }));
    fill("events", el("h2", { textContent: "events" }), el("div", { textContent: counts }), el("ol", {}, ...latest));
  }

  return { el, clock, run, legend, tiles, robotPanel, paramsForm, summary, bridge, events };
})();
