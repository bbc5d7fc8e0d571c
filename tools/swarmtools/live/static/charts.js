// charts.js - small line charts of the time series the server keeps
// (view.py): one chart a column, except the robots by state (state.<name>),
// drawn together in their states' colours.  Names and units come with the
// series: nothing here knows a controller, a task or a value.
"use strict";

const Charts = (() => {
  const STATES = "state.", SWARM = "swarm.";
  const PAD = { l: 4, r: 4, t: 16, b: 4 };

  // Chart keys in the series' order: "state." for all the states.
  function keys(series) {
    const out = [];
    for (const name of Object.keys(series.cols)) {
      const key = name.startsWith(STATES) ? STATES : name;
      if (!out.includes(key)) out.push(key);
    }
    return out;
  }

  function fmt(v) {
    if (v === null || v === undefined) return "-";
    if (Number.isInteger(v)) return String(v);
    return Math.abs(v) >= 1000 || Math.abs(v) < 0.01 ? v.toPrecision(4) : v.toFixed(3).replace(/\.?0+$/, "");
  }

  function last(col) {
    for (let k = col.length - 1; k >= 0; k--) if (col[k] !== null) return col[k];
    return null;
  }

  function canvasFor(box, key) {
    let c = box.querySelector(`canvas[data-key="${CSS.escape(key)}"]`);
    if (!c) {
      c = document.createElement("canvas");
      c.dataset.key = key;
      box.appendChild(c);
      c.width = c.clientWidth || 240;     // as wide as the page lays it out: sharp text
      c.height = c.clientHeight || 70;
    }
    return c;
  }

  // Lines of `cols` ([name, values, colour]) over series.t.
  function plot(c, t, cols, title) {
    const ctx = c.getContext("2d"), W = c.width, H = c.height;
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, W, H);
    ctx.fillStyle = "#222";
    ctx.font = "11px sans-serif";
    ctx.textBaseline = "top";
    ctx.fillText(title, PAD.l, 2);
    let lo = Infinity, hi = -Infinity;
    for (const [, v] of cols) for (const x of v) if (x !== null) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
    if (!t.length || lo === Infinity) return;
    if (hi === lo) { hi += 0.5; lo -= 0.5; }
    const t0 = t[0], t1 = t[t.length - 1] > t0 ? t[t.length - 1] : t0 + 1;
    const X = (x) => PAD.l + ((x - t0) / (t1 - t0)) * (W - PAD.l - PAD.r);
    const Y = (y) => H - PAD.b - ((y - lo) / (hi - lo)) * (H - PAD.t - PAD.b);
    ctx.lineWidth = 1.2;
    for (const [, v, colour] of cols) {
      ctx.strokeStyle = colour;
      ctx.beginPath();
      let pen = false;
      for (let k = 0; k < t.length; k++) {
        if (v[k] === null) { pen = false; continue; }
        if (pen) ctx.lineTo(X(t[k]), Y(v[k])); else ctx.moveTo(X(t[k]), Y(v[k]));
        pen = true;
      }
      ctx.stroke();
    }
  }

  // Draws every chart into `box`; returns the chart keys drawn.
  function render(box, series, colourOf) {
    const ks = keys(series);
    for (const key of ks) {
      const c = canvasFor(box, key);
      if (key === STATES) {
        const cols = Object.keys(series.cols).filter((n) => n.startsWith(STATES))
          .map((n) => [n, series.cols[n], colourOf(n.slice(STATES.length))]);
        plot(c, series.t, cols, "robots by state");
      } else {
        const col = series.cols[key], unit = series.units[key];
        const name = key.startsWith(SWARM) ? key.slice(SWARM.length) : key;
        plot(c, series.t, [[key, col, "#2b6cb0"]], `${name} ${fmt(last(col))}${unit ? " " + unit : ""}`);
      }
    }
    for (const c of [...box.querySelectorAll("canvas")]) if (!ks.includes(c.dataset.key)) c.remove();
    return ks;
  }

  return { render, fmt };
})();
