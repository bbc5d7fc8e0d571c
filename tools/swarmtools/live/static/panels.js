// panels.js - the page's text: the clock, what runs, robots by state (the
// legend), tiles for robots without a position, the run's summary, the
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

  function swatch(colour) {
    const s = el("span", { className: "swatch" });
    s.style.background = colour;
    return s;
  }

  function clock(model) {
    const parts = [];
    if (model.clock !== null && model.clock !== undefined) {
      parts.push(`t = ${model.clock.toFixed(1)} s`);
      const sw = model.swarm, steps = model.info ? model.info.steps : 0;
      if (sw) parts.push(`step ${sw.step}${steps ? ` of ${steps} (${Math.round((100 * sw.step) / steps)} %)` : ""}`);
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

  // Robots by state: the swarm's counts, or counted from the robots.
  function legend(model, robots, colourOf) {
    let states = model.swarm ? model.swarm.states : null;
    if (!states) {
      const n = new Map();
      robots.forEach((r) => n.set(r.state, (n.get(r.state) || 0) + 1));
      states = [...n.entries()];
    }
    fill("legend", ...states.map(([name, count]) => el("span", {}, swatch(colourOf(name)), `${name} ${count}`)));
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
  function tiles(model, unplaced, colourOf) {
    const box = fill("tiles", ...unplaced.map((rb) => {
      const age = model.time - rb.seen;
      const state = el("span", { className: "state", textContent: rb.state });
      state.style.background = colourOf(rb.state);
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

  return { el, clock, run, legend, tiles, summary, bridge, events };
})();
