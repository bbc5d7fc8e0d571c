// keys.js - the colour key of the robots and the things on the floor.  A
// simulation sends its legend with the scene (scene_t: the one its PNG
// frames and videos draw, sim_host/core/legend.h): a robot's body has the
// fill its task gives it (task_drawing_t), else the default body, and the
// legend lists those keys with the tasks' floor areas, outlines and items.
// Without one (real robots, a log from before the legend) a robot's body
// has a colour per controller state, in the order states are first seen.
"use strict";

const Keys = (() => {
  const PALETTE = ["#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1", "#edc948",
                   "#76b7b2", "#ff9da7", "#9c755f", "#bab0ac", "#2f4b7c", "#a05195"];
  const ROBOT = 0;              // drawing.h's draw_key_kind_t
  const states = new Map();     // kept across seeks, so a state keeps its colour

  const hex = (rgb) => "#" + ((rgb >>> 0) & 0xffffff).toString(16).padStart(6, "0");

  function stateColour(state) {
    if (!states.has(state)) states.set(state, PALETTE[states.size % PALETTE.length]);
    return states.get(state);
  }

  // The run's legend ([{kind, rgb, label}]), or null.
  const legend = (model) => (model.scene && model.scene.legend && model.scene.legend.length ? model.scene.legend : null);

  // A robot's body colour (CSS).
  function body(model, rb) {
    if (!legend(model)) return stateColour(rb.state);
    const fills = model.drawing ? model.drawing.fills : {};
    return hex(rb.id in fills ? fills[rb.id] : model.scene.robot_rgb);
  }

  // What the legend shows: [{kind, colour, label, count}] (count: robots
  // with that body colour, for robot keys; null for the others), from the
  // run's legend or else the controller states.
  function entries(model, robots) {
    const keys = legend(model);
    if (!keys) {
      let counts = model.swarm ? model.swarm.states : null;
      if (!counts) {
        const n = new Map();
        robots.forEach((r) => n.set(r.state, (n.get(r.state) || 0) + 1));
        counts = [...n.entries()];
      }
      return counts.map(([name, count]) => ({ kind: ROBOT, colour: stateColour(name), label: name, count }));
    }
    const bodies = new Map();
    for (const r of robots) {
      const c = body(model, r);
      bodies.set(c, (bodies.get(c) || 0) + 1);
    }
    return keys.map((k) => ({ kind: k.kind, colour: hex(k.rgb), label: k.label,
                              count: k.kind === ROBOT ? bodies.get(hex(k.rgb)) || 0 : null }));
  }

  return { hex, body, entries, legend, stateColour, stateColours: () => Object.fromEntries(states), ROBOT };
})();
