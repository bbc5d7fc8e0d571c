// charts.js - small line charts of the time series the server keeps
// (view.py): one chart a column, except the robots by state (state.<name>),
// drawn together in their states' colours; each with a time axis and an
// axis of its value in its unit, both with ticks.  Names and units come
// with the series: nothing here knows a controller, a task or a value.
"use strict";

const Charts = (() => {
  const STATES = "state.", SWARM = "swarm.";
  const PAD = { l: 40, r: 8, t: 18, b: 26 };   // px: room for the ticks' labels

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
      c.height = c.clientHeight || 120;
    }
    return c;
  }

  // Ticks at round values (1, 2 or 5 times a power of ten) about n over
  // [lo, hi], and the decimals their labels need.
  function ticks(lo, hi, n) {
    const raw = (hi - lo) / n, p = 10 ** Math.floor(Math.log10(raw));
    const step = [1, 2, 5, 10].map((k) => k * p).find((v) => v >= raw * (1 - 1e-9));
    const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    const out = [];
    for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k++) out.push(Number((k * step).toFixed(decimals)));
    return { at: out, label: (v) => (Math.abs(v) >= 1e5 ? v.toExponential(1) : v.toFixed(decimals)) };
  }

  // Lines of `cols` ([name, values, colour]) over series.t, with a time
  // axis (s) below and a value axis in `unit` on the left, each with ticks.
  // Returns the axes drawn ({x, y}: their labels and tick values), or null
  // when there was nothing to draw.
  function plot(c, t, cols, title, unit) {
    const ctx = c.getContext("2d"), W = c.width, H = c.height;
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, W, H);
    ctx.fillStyle = "#222";
    ctx.font = "11px sans-serif";
    ctx.textBaseline = "top";
    ctx.textAlign = "left";
    ctx.fillText(title, 2, 2);
    // Several lines: their names in their colours under the title, wrapped.
    let top = PAD.t, x = 2;
    if (cols.length > 1) {
      for (const [name, , colour] of cols) {
        const w = ctx.measureText(name).width;
        if (x > 2 && x + w > W - PAD.r) { x = 2; top += 13; }
        ctx.fillStyle = colour;
        ctx.fillText(name, x, top);
        x += w + 8;
      }
      top += 13;
    }
    let lo = Infinity, hi = -Infinity;
    for (const [, v] of cols) for (const x of v) if (x !== null) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
    if (!t.length || lo === Infinity) return null;
    if (hi === lo) { hi += 0.5; lo -= 0.5; }
    const t0 = t[0], t1 = t[t.length - 1] > t0 ? t[t.length - 1] : t0 + 1;
    const X = (x) => PAD.l + ((x - t0) / (t1 - t0)) * (W - PAD.l - PAD.r);
    const Y = (y) => H - PAD.b - ((y - lo) / (hi - lo)) * (H - top - PAD.b);
    const xt = ticks(t0, t1, Math.max(2, Math.floor((W - PAD.l - PAD.r) / 60)));
    const yt = ticks(lo, hi, Math.max(2, Math.floor((H - top - PAD.b) / 25)));
    const xLabel = "time (s)", yLabel = unit || "";
    ctx.strokeStyle = "#888";
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(PAD.l, top);
    ctx.lineTo(PAD.l, H - PAD.b);
    ctx.lineTo(W - PAD.r, H - PAD.b);
    for (const v of xt.at) { ctx.moveTo(X(v), H - PAD.b); ctx.lineTo(X(v), H - PAD.b + 3); }
    for (const v of yt.at) { ctx.moveTo(PAD.l - 3, Y(v)); ctx.lineTo(PAD.l, Y(v)); }
    ctx.stroke();
    ctx.font = "10px sans-serif";
    ctx.fillStyle = "#444";
    ctx.textAlign = "center";
    for (const v of xt.at) ctx.fillText(xt.label(v), X(v), H - PAD.b + 4);
    ctx.textAlign = "right";
    ctx.fillText(xLabel, W - PAD.r, H - 11);
    ctx.textBaseline = "middle";
    for (const v of yt.at) ctx.fillText(yt.label(v), PAD.l - 5, Y(v));
    if (yLabel) {     // the value's unit, along the value axis
      ctx.save();
      ctx.translate(8, (top + H - PAD.b) / 2);
      ctx.rotate(-Math.PI / 2);
      ctx.textAlign = "center";
      ctx.fillText(yLabel, 0, 0);
      ctx.restore();
    }
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
    return { x: { label: xLabel, ticks: xt.at.map(xt.label) }, y: { label: yLabel, ticks: yt.at.map(yt.label) },
             lines: cols.map(([name, , colour]) => ({ name, colour })) };
  }

  // Draws every chart into `box`; returns the chart keys drawn and each
  // one's axes (plot's).
  function render(box, series, colourOf) {
    const ks = keys(series), axes = {};
    for (const key of ks) {
      const c = canvasFor(box, key);
      if (key === STATES) {
        const names = Object.keys(series.cols).filter((n) => n.startsWith(STATES));
        const cols = names.map((n) => [n.slice(STATES.length), series.cols[n], colourOf(n.slice(STATES.length))]);
        axes[key] = plot(c, series.t, cols, "robots by state", series.units[names[0]]);
      } else {
        const col = series.cols[key], unit = series.units[key];
        const name = key.startsWith(SWARM) ? key.slice(SWARM.length) : key;
        axes[key] = plot(c, series.t, [[key, col, "#2b6cb0"]], `${name} ${fmt(last(col))}${unit ? " " + unit : ""}`, unit);
      }
    }
    for (const c of [...box.querySelectorAll("canvas")]) if (!ks.includes(c.dataset.key)) c.remove();
    return { keys: ks, axes };
  }

  return { render, fmt };
})();
