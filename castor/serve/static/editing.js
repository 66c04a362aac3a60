// Editing on screen (CLI.md, "Editing on screen"): a toolbar of Place, Move,
// Measure and Undo over castor's live preview. The pointer's ray is snapped on
// the exact solids by the server (POST /gesture, castor.snap) as it moves, the
// snapped feature shown by a marker and its name; clicks (or a drag) give the
// points, a typed number in the value box a distance or a height exactly, and
// each gesture becomes a text edit made by castor (the file under castor
// --serve, the editor's buffer under castor --lsp --serve), whose lines are
// shown as written. The page sends numbers and names only; nothing it sends is
// evaluated as text.
"use strict";

(function () {
  const viewer = window.castorViewer;
  if (!viewer) return;
  const $ = (id) => document.getElementById(id);
  const canvas = viewer.canvas;
  const CLICK = 4; // pixels: a press and release closer than this is a click

  const state = {
    tool: null, // "place", "move", "measure"
    points: [], // the snaps taken: {point, feature, source, path, version, ray}
    height: false, // Place waits for its height
    snap: null, // the last snap under the pointer
    pointer: null,
    down: null,
    inFlight: false,
    wanted: null, // the newest pointer position to snap, while one is on its way
    undo: 0,
  };

  // ---- vectors ----
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const round = (v) => +v.toFixed(4); // as shown
  // as sent in an edit: to a micrometre, so that a difference of two points
  // is written 0.3, not 0.30000000000000004
  const micro = (v) => +v.toFixed(6);

  // ---- the page's parts ----
  function element(tag, attributes, text) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attributes || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  const bar = element("span", { class: "group", id: "editing", role: "toolbar", "aria-label": "editing" });
  const tools = {};
  for (const [name, title] of [["Place", "a new primitive: two corners, then its height"],
    ["Move", "move an object: the face to take, then where to put it"],
    ["Measure", "distances, a face's area, an object's volume"]]) {
    const b = element("button", { id: `edit-${name.toLowerCase()}`, title, "aria-pressed": "false" }, name);
    b.addEventListener("click", () => choose(state.tool === name.toLowerCase() ? null : name.toLowerCase()));
    tools[name.toLowerCase()] = b;
    bar.append(b);
  }
  const primitive = element("select", { id: "edit-primitive", "aria-label": "primitive", title: "the primitive Place writes" });
  const colour = element("input", { id: "edit-colour", type: "color", value: "#cccccc", "aria-label": "colour", title: "its colour" });
  const undo = element("button", { id: "edit-undo", title: "undo the last edit made from this page", disabled: "" }, "Undo");
  const value = element("input", { id: "edit-value", "aria-label": "value", inputmode: "decimal",
    placeholder: "length", size: "8", title: "type a distance or a height, then Enter" });
  const named = element("input", { id: "edit-name", "aria-label": "name", placeholder: "name", size: "7",
    title: "the new object's name (else one from its primitive: bloc1, poteau2…)" });
  const into = element("input", { id: "edit-into", "aria-label": "into", placeholder: "into", size: "7",
    title: "an object $U(...) to add it to (else the list of the frame's '>')" });
  bar.append(primitive, colour, named, into, undo, value);
  $("bar").append(bar);

  const panel = element("section", { id: "edit-panel", "aria-live": "polite", hidden: "" });
  const prompt = element("div", { id: "edit-prompt" });
  const error = element("div", { id: "edit-error", hidden: "" });
  const result = element("pre", { id: "edit-result", title: "the text the last gesture wrote" });
  panel.append(prompt, error, result);
  const marker = element("div", { id: "edit-marker", hidden: "" });
  const feature = element("div", { id: "edit-feature", hidden: "" });
  // the rubber band: from the first point to the one under the pointer (Place:
  // the box's outline), drawn over the canvas, with the running length
  const SVG = "http://www.w3.org/2000/svg";
  const band = document.createElementNS(SVG, "svg");
  band.id = "edit-band";
  band.setAttribute("aria-hidden", "true");
  // styled through the CSSOM: the page's policy refuses style attributes
  Object.assign(band.style, { position: "absolute", left: "0", top: "0", width: "100%", height: "100%",
    pointerEvents: "none", zIndex: "1", overflow: "hidden" });
  const bandPath = document.createElementNS(SVG, "path");
  bandPath.setAttribute("fill", "none");
  bandPath.setAttribute("stroke", "#0a7d2c");
  bandPath.setAttribute("stroke-width", "2");
  bandPath.setAttribute("stroke-linejoin", "round");
  band.append(bandPath);
  const bandLength = element("div", { id: "edit-length", role: "status", "aria-label": "length", hidden: "" });
  Object.assign(bandLength.style, { position: "absolute", padding: "1px 5px", fontSize: "11px",
    pointerEvents: "none", zIndex: "1", background: "rgba(255, 255, 255, 0.9)", border: "1px solid #0a7d2c",
    borderRadius: "3px", fontFamily: "ui-monospace, 'DejaVu Sans Mono', monospace", whiteSpace: "nowrap" });
  canvas.parentElement.append(panel, band, marker, feature, bandLength);

  // ---- the server ----
  async function gesture(command, args) {
    const answer = await fetch("/gesture", {
      method: "POST", headers: { "Content-Type": "application/json" }, cache: "no-store",
      body: JSON.stringify({ command, arguments: args || {} }),
    });
    const data = await answer.json().catch(() => ({ error: "no answer from castor" }));
    if (!answer.ok) throw new Error(data.error || answer.statusText);
    return data;
  }

  // The ray under a point of the canvas (CSS pixels), as the view is drawn.
  function ray(x, y) {
    const cam = viewer.camera();
    const { towards, forward, right, up } = viewer.basis(cam);
    const w = canvas.clientWidth, h = Math.max(1, canvas.clientHeight);
    const t = Math.tan(viewer.FOV / 2);
    const sx = ((2 * x) / w - 1) * t * (w / h), sy = (1 - (2 * y) / h) * t;
    const eye = add(cam.target, scale(towards, cam.distance));
    if (cam.ortho) {
      const across = add(scale(right, sx * cam.distance), scale(up, sy * cam.distance));
      const back = scale(forward, -(cam.distance + 3 * viewer.radius()));
      return { origin: add(add(eye, across), back), direction: forward, pixelSize: (2 * cam.distance * t) / h };
    }
    return { origin: eye, direction: add(forward, add(scale(right, sx), scale(up, sy))), pixel: (2 * t) / h };
  }

  // Where a scene point is drawn on the canvas (CSS pixels), or null behind the eye.
  function project(p) {
    const w = canvas.clientWidth, h = Math.max(1, canvas.clientHeight);
    const m = viewer.matrices(w / h).matrix;
    const clip = [0, 1, 2, 3].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
    if (clip[3] <= 0) return null;
    return [((clip[0] / clip[3] + 1) / 2) * w, ((1 - clip[1] / clip[3]) / 2) * h];
  }
  viewer.project = project;

  function frameNumber() {
    const meta = viewer.frame();
    return meta ? meta.number : 1;
  }

  function snapArguments(x, y, distance) {
    const r = ray(x, y);
    const args = { frame: frameNumber(), origin: r.origin, direction: r.direction };
    if (r.pixelSize !== undefined) args.pixelSize = r.pixelSize;
    else args.pixel = r.pixel;
    const last = state.points[state.points.length - 1];
    if (last) args.from = last.point;
    if (distance !== undefined) args.distance = distance;
    return { args, ray: r };
  }

  async function snapAt(x, y, distance) {
    const { args, ray: r } = snapArguments(x, y, distance);
    const answer = await gesture("castor.snap", args);
    return answer.result ? Object.assign({ version: answer.version, ray: r }, answer.result) : null;
  }

  // ---- what is shown ----
  function say(text) {
    prompt.textContent = text;
    panel.hidden = false;
  }

  function fail(message) {
    error.textContent = message;
    error.hidden = false;
    document.body.dataset.editError = message;
  }

  function showSnap(snap) {
    state.snap = snap;
    const at = snap && project(snap.point);
    if (!at) {
      marker.hidden = feature.hidden = true;
      delete document.body.dataset.snapped;
      startBand();
      return;
    }
    marker.style.left = `${at[0]}px`;
    marker.style.top = `${at[1]}px`;
    marker.className = snap.feature.replace(/\s+/g, "-");
    feature.style.left = `${at[0] + 10}px`;
    feature.style.top = `${at[1] + 8}px`;
    feature.textContent = [snap.feature, snap.source, snap.path].filter(Boolean).join(" · ");
    marker.hidden = feature.hidden = false;
    document.body.dataset.snapped = snap.feature;
    startBand();
  }

  // ---- the rubber band ----
  // The segments (pairs of scene points) and the length shown between the
  // first point and the one under the pointer, or null.
  function stretched() {
    const first = state.points[0], now = state.snap;
    if (!state.tool || !first || !now || !now.point) return null;
    const a = first.point, b = now.point;
    if (state.tool !== "place") {
      const d = sub(b, a);
      return { segments: [[a, b]], text: `${round(Math.hypot(d[0], d[1], d[2]))} m`, at: [a, b] };
    }
    // Place: the box's outline, its base in the first corner's plane across
    // the side the two corners leave flat (as place() writes it)
    const second = state.height ? state.points[1].point : b;
    const size = sub(second, a);
    let flat = 2;
    for (const k of [0, 1, 2]) if (Math.abs(size[k]) < Math.abs(size[flat]) - 1e-9) flat = k;
    const [u, v] = [0, 1, 2].filter((k) => k !== flat);
    const corner = (du, dv, dh) => {
      const p = a.slice();
      p[u] += du ? size[u] : 0;
      p[v] += dv ? size[v] : 0;
      p[flat] += dh;
      return p;
    };
    const ring = (h) => [[corner(0, 0, h), corner(1, 0, h)], [corner(1, 0, h), corner(1, 1, h)],
      [corner(1, 1, h), corner(0, 1, h)], [corner(0, 1, h), corner(0, 0, h)]];
    const sides = `${round(Math.abs(size[u]))} × ${round(Math.abs(size[v]))}`;
    if (!state.height) return { segments: ring(0), text: `${sides} m`, at: [a, second] };
    const h = state.dragged || 0;
    const segments = ring(0);
    if (h) {
      segments.push(...ring(h));
      for (const [du, dv] of [[0, 0], [1, 0], [1, 1], [0, 1]]) segments.push([corner(du, dv, 0), corner(du, dv, h)]);
    }
    return { segments, text: h ? `${sides} × ${round(Math.abs(h))} m` : `${sides} m`, at: [a, corner(0, 0, h)] };  // the upright away from the pointer's
  }

  let bandShown = "";
  function drawBand() {
    const drawn = stretched();
    let path = "", label = null;
    if (drawn) {
      for (const [p, q] of drawn.segments) {
        const s = project(p), e = project(q);
        if (s && e) path += `M${s[0].toFixed(1)} ${s[1].toFixed(1)}L${e[0].toFixed(1)} ${e[1].toFixed(1)}`;
      }
      const s = project(drawn.at[0]), e = project(drawn.at[1]);
      if (path && s && e) label = [(s[0] + e[0]) / 2, (s[1] + e[1]) / 2];
    }
    const key = `${path}|${drawn && label ? drawn.text : ""}|${label}`;
    if (key === bandShown) return;
    bandShown = key;
    bandPath.setAttribute("d", path);
    if (!label) {
      bandLength.hidden = true;
      delete document.body.dataset.band;
      return;
    }
    bandLength.textContent = drawn.text;
    bandLength.style.left = `${label[0] + 8}px`;
    bandLength.style.top = `${label[1] - 22}px`;
    bandLength.hidden = false;
    document.body.dataset.band = drawn.text;
  }

  // While a gesture is under way the band follows the view too (turned,
  // zoomed): re-projected at each animation frame, redrawn only if it moved.
  let banding = false;
  function followBand() {
    drawBand();
    banding = Boolean(state.tool && state.points.length);
    if (banding) requestAnimationFrame(followBand);
  }
  function startBand() {
    if (!banding) followBand();
    else drawBand();
  }

  function showWritten(lines) {
    result.textContent = lines.map((l) => `${l.file}:${l.line}  ${l.text}`).join("\n");
    document.body.dataset.written = String(Number(document.body.dataset.written || 0) + 1);
  }

  function showUndo(count) {
    state.undo = count;
    if (count) undo.removeAttribute("disabled");
    else undo.setAttribute("disabled", "");
  }

  const PROMPTS = {
    place: ["Place: click a corner of its box", "the opposite corner (or type its sides x, y, Enter)",
      "its height: drag it and click, or type it and press Enter (1 m)"],
    move: ["Move: click the face to take", "where to put it (or type a distance, Enter)"],
    measure: ["Measure: click a point, a face or an object", "the second point (or type a distance, Enter)"],
  };

  function prompted() {
    document.body.dataset.points = String(state.points.length);
    startBand();
    if (!state.tool) {
      panel.hidden = !result.textContent;
      prompt.textContent = "";
      return;
    }
    const step = state.height ? 2 : Math.min(state.points.length, 1);
    say(PROMPTS[state.tool][step]);
    value.placeholder = state.height ? "height" : "length";
  }

  function choose(tool) {
    state.tool = tool;
    state.points = [];
    state.height = false;
    for (const [name, b] of Object.entries(tools)) {
      b.classList.toggle("active", name === tool);
      b.setAttribute("aria-pressed", String(name === tool));
    }
    canvas.style.cursor = tool ? "crosshair" : "";
    if (!tool) showSnap(null);
    error.hidden = true;
    prompted();
  }

  // ---- the gestures ----
  async function take(snap) {
    error.hidden = true;
    if (!snap) {
      fail("nothing to snap to here");
      return;
    }
    if (state.tool === "move" && !state.points.length && !snap.source) {
      fail("click a face of an object to move it");
      return;
    }
    state.points.push(snap);
    if (state.pointer) {  // snapped again from the new point (axes, parallels)
      state.wanted = state.pointer;
      follow();
    }
    if (state.points.length === 1) {
      if (state.tool === "measure") await measureFirst(snap);
      prompted();
      return;
    }
    const [first, second] = state.points;
    if (state.tool === "place") {
      state.height = true;
      state.dragged = null;
      prompted();
      value.focus();
      return;
    }
    if (state.tool === "move") {
      await edit("castor.move", { frame: frameNumber(), source: first.source, path: first.path,
        by: sub(second.point, first.point).map(micro), version: first.version });
    } else {
      const m = (await gesture("castor.measure", { from: first.point, to: second.point })).result;
      result.textContent = `distance ${round(m.distance)} m · dx ${round(m.dx)} · dy ${round(m.dy)} · dz ${round(m.dz)}`;
      document.body.dataset.measured = result.textContent;
    }
    state.points = [];
    prompted();
  }

  async function measureFirst(snap) {
    const lines = [`point ${snap.point.map(round).join(", ")} (${snap.feature})`];
    if (snap.path) {
      // the face under the pointer, if it is the snapped object's: a corner
      // snapped beside an outline has the ground or another face behind it
      const face = (await gesture("castor.measure", { frame: frameNumber(), origin: snap.ray.origin,
        direction: snap.ray.direction }).catch(() => ({}))).result;
      if (face && face.area !== undefined && face.path === snap.path) lines.push(`face ${round(face.area)} m²`);
      const name = /^\(([^)]+)\)/.exec(snap.path);
      if (name) {
        const o = (await gesture("castor.measure", { frame: frameNumber(), object: name[1] })).result;
        if (o && o.volume !== undefined) {
          lines.push(`${name[1]}: volume ${round(o.volume)} m³, box ` +
            `${o.box[0].map(round).join(", ")} to ${o.box[1].map(round).join(", ")}`);
        }
      }
    }
    result.textContent = lines.join("\n");
    document.body.dataset.measured = result.textContent;
  }

  function hexColour() {
    const hex = colour.value.replace("#", "");
    return [0, 2, 4].map((i) => round(parseInt(hex.slice(i, i + 2), 16) / 255));
  }

  async function place(height) {
    const [first, second] = state.points;
    const size = sub(second.point, first.point).map(micro);
    // the side the two corners leave flat takes the height
    let flat = 2;
    for (const k of [0, 1, 2]) if (Math.abs(size[k]) < Math.abs(size[flat]) - 1e-9) flat = k;
    size[flat] = height;
    const args = { frame: frameNumber(), primitive: primitive.value, colour: hexColour(),
      at: first.point.map(micro), size, version: first.version };
    if (named.value.trim()) args.name = named.value.trim();
    if (into.value.trim()) args.into = into.value.trim();
    await edit("castor.place", args);
    state.points = [];
    state.height = false;
    prompted();
  }

  async function edit(command, args) {
    try {
      const answer = await gesture(command, args);
      showWritten(answer.written);
      showUndo(answer.undo);
    } catch (e) {
      fail(e.message);
    }
  }

  undo.addEventListener("click", async () => {
    error.hidden = true;
    try {
      const answer = await gesture("undo");
      showWritten(answer.written);
      showUndo(answer.undo);
      panel.hidden = false;
    } catch (e) {
      fail(e.message);
      panel.hidden = false;
    }
  });

  // The value box: a number (never text for castor to read) and Enter.
  value.addEventListener("keydown", async (e) => {
    if (e.key === "Escape") {
      choose(state.tool);
      return;
    }
    if (e.key !== "Enter" || !state.tool) return;
    const typed = value.value.trim();
    const number = typed === "" ? NaN : Number(typed);
    value.value = "";
    then(async () => {
      if (state.height) {
        if (typed !== "" && !(Number.isFinite(number) && number !== 0)) throw new Error(`'${typed}' is not a height`);
        await place(typed === "" ? 1 : number);
      } else if (state.tool === "place" && state.points.length === 1 && /^[^,]+,[^,]+$/.test(typed)) {
        // "x, y": the box's sides along x and y, on the first corner's level
        const sides = typed.split(",").map((v) => Number(v.trim()));
        if (!sides.every((v) => Number.isFinite(v) && v !== 0)) throw new Error(`'${typed}' is not two sides`);
        const first = state.points[0];
        await take(Object.assign({}, first, { point: add(first.point, [sides[0], sides[1], 0]) }));
      } else if (state.points.length) {
        if (!Number.isFinite(number) || number <= 0) throw new Error(`'${typed}' is not a distance`);
        const at = state.pointer || [canvas.clientWidth / 2, canvas.clientHeight / 2];
        await take(await snapAt(at[0], at[1], number));
      }
    });
  });

  document.addEventListener("keydown", (e) => {
    if (e.key === "Escape" && state.tool && e.target !== value) choose(state.tool);
  });

  // ---- the pointer: snapped as it moves; a click (or a drag) takes points ----
  function where(e) {
    const rect = canvas.getBoundingClientRect();
    return [e.clientX - rect.left, e.clientY - rect.top];
  }

  async function follow() {
    if (state.inFlight || !state.wanted) return;
    const [x, y] = state.wanted;
    state.wanted = null;
    state.inFlight = true;
    try {
      const snap = await snapAt(x, y);
      if (state.tool && !state.height) showSnap(snap);
    } catch (e) {
      showSnap(null);
    } finally {
      state.inFlight = false;
      follow();
    }
  }

  // Place's height dragged: the height above the second corner whose point is
  // drawn nearest the pointer, on a 0.05 m grid (none where z is not seen rise)
  function draggedHeight(pointer) {
    const corner = state.points[1].point;
    const base = project(corner), top = project(add(corner, [0, 0, 1]));
    if (!base || !top) return null;
    const d = [top[0] - base[0], top[1] - base[1]];
    const length = d[0] * d[0] + d[1] * d[1];
    if (length < 1) return null;
    const h = ((pointer[0] - base[0]) * d[0] + (pointer[1] - base[1]) * d[1]) / length;
    const rounded = Math.round(h / 0.05) * 0.05;
    return Math.abs(rounded) < 0.05 ? null : round(rounded);
  }

  function showHeight(pointer) {
    state.dragged = draggedHeight(pointer);
    if (state.dragged === null) return;
    say(`its height: ${state.dragged} m — click, or type it and press Enter`);
    showSnap({ point: add(state.points[1].point, [0, 0, state.dragged]), feature: `height ${state.dragged}` });
    document.body.dataset.height = String(state.dragged);
  }

  const own = (e) => state.tool && e.button === 0 && !e.shiftKey;
  const area = canvas.parentElement;
  area.addEventListener("pointermove", (e) => {
    if (!state.tool || e.target !== canvas) return;
    state.pointer = where(e);
    if (state.height) {
      showHeight(state.pointer);
      return;
    }
    state.wanted = state.pointer;
    follow();
  }, true);
  // Each point is taken after the one before it (its snap starts from it),
  // however quickly the clicks and the keys come.
  function then(step) {
    state.taking = state.taking.then(async () => {
      try {
        await step();
      } catch (err) {
        fail(err.message);
      }
    });
    return state.taking;
  }
  state.taking = Promise.resolve();

  area.addEventListener("pointerdown", (e) => {
    if (!own(e) || e.target !== canvas) return;
    e.stopImmediatePropagation();
    const down = where(e);
    state.down = down;
    then(async () => {
      if (!state.height) {
        await take(await snapAt(...down));
        return;
      }
      const height = draggedHeight(down);
      if (height !== null) await place(height);
    });
  }, true);
  area.addEventListener("pointerup", (e) => {
    if (!own(e) || !state.down) return;
    e.stopImmediatePropagation();
    const down = state.down, up = where(e);
    state.down = null;
    if (Math.abs(up[0] - down[0]) + Math.abs(up[1] - down[1]) < CLICK) return;
    then(async () => {
      // a drag: its end is the next point
      if (state.points.length && !state.height) await take(await snapAt(...up));
    });
  }, true);

  // ---- what the server offers ----
  fetch("/editing.json", { cache: "no-store" }).then((r) => r.json()).then((offer) => {
    for (const p of offer.primitives) primitive.append(element("option", { value: p }, p));
    showUndo(offer.undo || 0);
    if (!offer.enabled) {
      bar.hidden = true;
      return;
    }
    document.body.dataset.editing = "ready";
  });
})();
