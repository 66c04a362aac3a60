// castor's live preview: draws the frames that `castor --serve` evaluates, with
// WebGL, and swaps in new ones when the server says the scene has changed.
// z is up, as in castor's scenes; a camera is an azimuth around z from +x and an
// elevation above the horizon, as castor's --view takes them.
"use strict";

(function () {
  const $ = (id) => document.getElementById(id);
  const canvas = $("view");
  const FOV = (40 * Math.PI) / 180;
  const BACKGROUND = [1, 1, 1];
  // name: [azimuth, elevation, orthographic], as castor's --view names them
  const VIEWS = {
    top: [-90, 90, true],
    front: [-90, 0, true],
    side: [0, 0, true],
    perspective: [-60, 25, false],
  };

  const state = {
    server: null, // the name of the castor --serve that answers
    version: -1, // of the scene.json shown
    scene: null,
    frames: [], // {meta, mesh}
    framesKey: "",
    current: 0,
    timer: null, // playing the frames
    box: null, // of every frame
    camera: { target: [0, 0, 0], distance: 10, azimuth: -60, elevation: 25, ortho: false },
    fitted: false,
    cut: Infinity, // the section plane's height
    pointer: null, // where the mouse is over the canvas, in CSS pixels
    drag: null,
    hidden: new Set(), // the layers (classes, or "unclassed") not drawn
  };

  // ---- vectors and matrices (column-major, as WebGL reads them) ----
  const rad = (d) => (d * Math.PI) / 180;
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

  function multiply(p, v) {
    const out = new Float32Array(16);
    for (let c = 0; c < 4; c++)
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += p[k * 4 + r] * v[c * 4 + k];
        out[c * 4 + r] = s;
      }
    return out;
  }

  // The camera's axes: towards the eye from the target, forward, right and up.
  function basis(cam) {
    const az = rad(cam.azimuth), el = rad(cam.elevation);
    const towards = [Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el)];
    const forward = scale(towards, -1);
    const right = [-Math.sin(az), Math.cos(az), 0]; // defined even looking straight down
    const up = cross(right, forward);
    return { towards, forward, right, up };
  }

  function radius() {
    if (!state.box) return 1;
    const [lo, hi] = state.box;
    return Math.max(0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 1e-6);
  }

  function matrices(aspect) {
    const cam = state.camera;
    const { towards, forward, right, up } = basis(cam);
    const eye = add(cam.target, scale(towards, cam.distance));
    const view = new Float32Array([
      right[0], up[0], -forward[0], 0,
      right[1], up[1], -forward[1], 0,
      right[2], up[2], -forward[2], 0,
      -dot(right, eye), -dot(up, eye), dot(forward, eye), 1,
    ]);
    const r = radius();
    let projection;
    if (cam.ortho) {
      const h = cam.distance * Math.tan(FOV / 2), w = h * aspect;
      const near = -(cam.distance + 3 * r), far = cam.distance + 3 * r;
      projection = [1 / w, 0, 0, 0, 0, 1 / h, 0, 0, 0, 0, -2 / (far - near), 0,
        0, 0, -(far + near) / (far - near), 1];
    } else {
      const f = 1 / Math.tan(FOV / 2);
      const near = Math.max(cam.distance - 3 * r, cam.distance / 200), far = cam.distance + 3 * r;
      projection = [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
        0, 0, (2 * far * near) / (near - far), 0];
    }
    return { matrix: multiply(projection, view), eye, forward };
  }

  // ---- WebGL ----
  const gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });

  const DRAW_VERTEX = `
    attribute vec3 position; attribute vec3 normal; attribute vec3 colour;
    uniform mat4 matrix; uniform vec3 eye; uniform vec3 forward; uniform float ortho;
    varying vec3 vNormal; varying vec3 vColour; varying vec3 vToEye; varying float vZ;
    void main() {
      vNormal = normal; vColour = colour; vZ = position.z;
      vToEye = mix(eye - position, -forward, ortho);
      gl_Position = matrix * vec4(position, 1.0);
    }`;
  // Light as castor's pictures: a face turned to the viewer shows its own colour at
  // full strength, faces turned away are darker, and the sky lightens those that
  // face up, so that the three visible faces of a box are told apart. The inside
  // of a solid, seen through the section plane, is greyed.
  const DRAW_FRAGMENT = `
    precision highp float;
    uniform float cut;
    varying vec3 vNormal; varying vec3 vColour; varying vec3 vToEye; varying float vZ;
    void main() {
      if (vZ > cut) discard;
      vec3 n = normalize(vNormal);
      if (!gl_FrontFacing) n = -n;
      float facing = max(dot(n, normalize(vToEye)), 0.0);
      float light = clamp(0.42 + 0.58 * facing + 0.12 * n.z, 0.0, 1.0);
      vec3 c = vColour * light;
      if (!gl_FrontFacing) c = mix(c, vec3(0.3), 0.6);
      gl_FragColor = vec4(c, 1.0);
    }`;
  const PICK_VERTEX = `
    attribute vec3 position; attribute vec4 pick;
    uniform mat4 matrix;
    varying vec4 vPick; varying float vZ;
    void main() { vPick = pick; vZ = position.z; gl_Position = matrix * vec4(position, 1.0); }`;
  const PICK_FRAGMENT = `
    precision highp float;
    uniform float cut;
    varying vec4 vPick; varying float vZ;
    void main() { if (vZ > cut) discard; gl_FragColor = vPick; }`;

  function program(vertex, fragment) {
    const p = gl.createProgram();
    for (const [kind, text] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
      const s = gl.createShader(kind);
      gl.shaderSource(s, text);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(p, s);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    const where = {};
    const attributes = gl.getProgramParameter(p, gl.ACTIVE_ATTRIBUTES);
    for (let i = 0; i < attributes; i++) {
      const name = gl.getActiveAttrib(p, i).name;
      where[name] = gl.getAttribLocation(p, name);
    }
    const uniforms = gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < uniforms; i++) {
      const name = gl.getActiveUniform(p, i).name;
      where[name] = gl.getUniformLocation(p, name);
    }
    return { p, where };
  }

  const drawing = gl && program(DRAW_VERTEX, DRAW_FRAGMENT);
  const picking = gl && program(PICK_VERTEX, PICK_FRAGMENT);
  const pickTarget = { framebuffer: null, texture: null, depth: null, width: 0, height: 0 };

  // The layer of a face: its element's class (LANGUAGE.md §11), or "unclassed".
  const UNCLASSED = "unclassed";
  const layerOf = (origin) => (origin && origin.class) || UNCLASSED;
  const byLayer = (a, b) => (a === UNCLASSED) - (b === UNCLASSED) || (a < b ? -1 : a > b ? 1 : 0);

  // The triangles of the layers shown, one range each.
  function drawLayers(mesh) {
    for (const layer of mesh.layers)
      if (layer.count && !state.hidden.has(layer.name)) gl.drawArrays(gl.TRIANGLES, layer.first, layer.count);
  }

  // A frame's triangles, each with its own three corners so that it is shaded
  // flat and carries its own number for picking; put in order of their layers,
  // so that a layer is one range of them, drawn or left out at once.
  function buildMesh(meta, bytes) {
    const n = meta.triangles;
    const given = new Float32Array(bytes, 0, n * 9);
    const givenOrigins = new Uint32Array(bytes, n * 36, n);
    const names = [...new Set(meta.origins.map(layerOf))].sort(byLayer);
    const rank = new Map(names.map((name, i) => [name, i]));
    const counts = new Array(names.length).fill(0);
    const layerOfOrigin = meta.origins.map((o) => rank.get(layerOf(o)));
    for (let t = 0; t < n; t++) counts[layerOfOrigin[givenOrigins[t]] || 0]++;
    const starts = [];
    let first = 0;
    const layers = names.map((name, i) => {
      starts.push(first);
      const layer = { name, first: first * 3, count: counts[i] * 3 };
      first += counts[i];
      return layer;
    });
    const corners = new Float32Array(n * 9);
    const origins = new Uint32Array(n);
    for (let t = 0; t < n; t++) {
      const to = starts[layerOfOrigin[givenOrigins[t]] || 0]++;
      corners.set(given.subarray(t * 9, t * 9 + 9), to * 9);
      origins[to] = givenOrigins[t];
    }
    const normals = new Float32Array(n * 9);
    const colours = new Float32Array(n * 9);
    const picks = new Uint8Array(n * 12);
    const palette = meta.origins.map((o) => o.colour);
    for (let t = 0; t < n; t++) {
      const i = t * 9;
      const ux = corners[i + 3] - corners[i], uy = corners[i + 4] - corners[i + 1], uz = corners[i + 5] - corners[i + 2];
      const vx = corners[i + 6] - corners[i], vy = corners[i + 7] - corners[i + 1], vz = corners[i + 8] - corners[i + 2];
      let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const length = Math.hypot(nx, ny, nz) || 1;
      nx /= length; ny /= length; nz /= length;
      const colour = palette[origins[t]] || [0.5, 0.5, 0.5];
      const id = t + 1;
      for (let k = 0; k < 3; k++) {
        normals[i + 3 * k] = nx; normals[i + 3 * k + 1] = ny; normals[i + 3 * k + 2] = nz;
        colours[i + 3 * k] = colour[0]; colours[i + 3 * k + 1] = colour[1]; colours[i + 3 * k + 2] = colour[2];
        const j = t * 12 + 4 * k;
        picks[j] = id & 255; picks[j + 1] = (id >> 8) & 255; picks[j + 2] = (id >> 16) & 255;
        picks[j + 3] = (id >>> 24) & 255;
      }
    }
    const upload = (data) => {
      const b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      return b;
    };
    return {
      count: n * 3, origins, layers,
      position: upload(corners), normal: upload(normals), colour: upload(colours), pick: upload(picks),
    };
  }

  function freeMesh(mesh) {
    if (!mesh) return;
    for (const b of [mesh.position, mesh.normal, mesh.colour, mesh.pick]) gl.deleteBuffer(b);
  }

  function attribute(where, name, buffer, size, type, normalized) {
    const at = where[name];
    if (at === undefined) return;
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, type, normalized, 0, 0);
  }

  function disableAttributes(where) {
    for (const name of ["position", "normal", "colour", "pick"])
      if (where[name] !== undefined) gl.disableVertexAttribArray(where[name]);
  }

  function resize() {
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(canvas.clientHeight * ratio));
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
  }

  const shown = () => state.frames[state.current];

  function draw() {
    if (!gl) return;
    resize();
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const frame = shown();
    if (!frame || !frame.mesh.count) return;
    gl.enable(gl.DEPTH_TEST);
    const { matrix, eye, forward } = matrices(canvas.width / canvas.height);
    const w = drawing.where;
    gl.useProgram(drawing.p);
    gl.uniformMatrix4fv(w.matrix, false, matrix);
    gl.uniform3fv(w.eye, eye);
    gl.uniform3fv(w.forward, forward);
    gl.uniform1f(w.ortho, state.camera.ortho ? 1 : 0);
    gl.uniform1f(w.cut, Number.isFinite(state.cut) ? state.cut : 3.0e38);
    attribute(w, "position", frame.mesh.position, 3, gl.FLOAT, false);
    attribute(w, "normal", frame.mesh.normal, 3, gl.FLOAT, false);
    attribute(w, "colour", frame.mesh.colour, 3, gl.FLOAT, false);
    drawLayers(frame.mesh);
    disableAttributes(w);
    document.body.dataset.hidden = [...state.hidden].sort(byLayer).join(" ");
  }

  let drawPending = false;
  function redraw() {
    if (drawPending) return;
    drawPending = true;
    requestAnimationFrame(() => {
      drawPending = false;
      draw();
      pointAt();
    });
  }

  // The triangle under the pointer: each triangle drawn in its own number's
  // colour into a hidden framebuffer, and the pixel read back.
  function pickedTriangle(x, y) {
    const frame = shown();
    if (!gl || !frame || !frame.mesh.count) return -1;
    const width = canvas.width, height = canvas.height;
    if (pickTarget.width !== width || pickTarget.height !== height) {
      if (pickTarget.framebuffer) {
        gl.deleteFramebuffer(pickTarget.framebuffer);
        gl.deleteTexture(pickTarget.texture);
        gl.deleteRenderbuffer(pickTarget.depth);
      }
      pickTarget.texture = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, pickTarget.texture);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, width, height, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      pickTarget.depth = gl.createRenderbuffer();
      gl.bindRenderbuffer(gl.RENDERBUFFER, pickTarget.depth);
      gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT16, width, height);
      pickTarget.framebuffer = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, pickTarget.framebuffer);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, pickTarget.texture, 0);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, pickTarget.depth);
      pickTarget.width = width;
      pickTarget.height = height;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, pickTarget.framebuffer);
    gl.viewport(0, 0, width, height);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    const w = picking.where;
    gl.useProgram(picking.p);
    gl.uniformMatrix4fv(w.matrix, false, matrices(width / height).matrix);
    gl.uniform1f(w.cut, Number.isFinite(state.cut) ? state.cut : 3.0e38);
    attribute(w, "position", frame.mesh.position, 3, gl.FLOAT, false);
    attribute(w, "pick", frame.mesh.pick, 4, gl.UNSIGNED_BYTE, true);
    drawLayers(frame.mesh);
    disableAttributes(w);
    const ratio = width / canvas.clientWidth;
    const pixel = new Uint8Array(4);
    const px = Math.min(width - 1, Math.max(0, Math.floor(x * ratio)));
    const py = Math.min(height - 1, Math.max(0, height - 1 - Math.floor(y * ratio)));
    gl.readPixels(px, py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    // the number of the triangle plus one, in four bytes; 0 where none was drawn
    return pixel[0] + pixel[1] * 256 + pixel[2] * 65536 + pixel[3] * 16777216 - 1;
  }

  // Say what is under the pointer: the path of its primitive, its element and
  // class, its colour and the FILE:LINE of the frame's '>' command.
  function pointAt() {
    const box = $("pointed");
    const frame = shown();
    if (!state.pointer || state.drag || !frame) {
      box.hidden = true;
      return;
    }
    const t = pickedTriangle(state.pointer[0], state.pointer[1]);
    if (t < 0 || t >= frame.meta.triangles) {
      box.hidden = true;
      return;
    }
    const origin = frame.meta.origins[frame.mesh.origins[t]];
    const c = origin.colour;
    $("pointed-path").textContent = origin.path;
    $("pointed-element").textContent = `${origin.element || frame.meta.where} · ${layerOf(origin)}`;
    $("pointed-colour").textContent = c.map((v) => +v.toFixed(3)).join(" ");
    $("pointed-swatch").style.background =
      `rgb(${c.map((v) => Math.round(Math.min(1, Math.max(0, v)) * 255)).join(",")})`;
    $("pointed-where").textContent = `frame ${frame.meta.number} · ${frame.meta.where}`;
    // where the primitive is written: a click copies it (vi +LINE FILE, or a jump)
    $("pointed-source").textContent = origin.source || "";
    state.pointedSource = origin.source || null;
    box.hidden = false;
  }

  // A face's FILE:LINE:COL to the clipboard; the page says so (and keeps it
  // in the document for whoever reads it where no clipboard is allowed).
  function copied(source) {
    const text = source.replace(/: ![a-z]+$/, "");
    document.body.dataset.copied = text;
    const done = () => { $("status").textContent = `copied ${text}`; };
    if (navigator.clipboard && navigator.clipboard.writeText) {
      navigator.clipboard.writeText(text).then(done, done);
    } else {
      done();
    }
  }

  // ---- the camera ----
  function fit(tell = true) {
    if (!state.box) return;
    const [lo, hi] = state.box;
    state.camera.target = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
    const aspect = canvas.clientWidth / Math.max(1, canvas.clientHeight);
    const half = Math.min(FOV / 2, Math.atan(Math.tan(FOV / 2) * aspect));
    state.camera.distance = (radius() / Math.sin(half)) * 1.02;
    redraw();
    if (tell) cameraStopped();
  }

  function setView(name) {
    const [azimuth, elevation, ortho] = VIEWS[name];
    Object.assign(state.camera, { azimuth, elevation, ortho });
    for (const other of Object.keys(VIEWS)) $(`view-${other}`).classList.toggle("active", other === name);
    redraw();
    cameraStopped();
  }

  // Once the camera stops (a turn, a pan or a zoom ended, a view chosen), the
  // server is told where it is, so that it facets the curved surfaces for it
  // (CLI.md, "Live preview": --pixel-error 0.5), and new frames follow.
  const CAMERA_PAUSE = 300; // ms without a move before the camera counts as stopped
  let cameraTimer = null, cameraSent = "";
  function cameraStopped() {
    clearTimeout(cameraTimer);
    cameraTimer = setTimeout(sendCamera, CAMERA_PAUSE);
  }

  // The server answers once the frames faceted for the camera are shown (or
  // after a few seconds): with the version then shown.
  async function sendCamera() {
    if (state.drag) return cameraStopped();
    if (!gl || !state.box || !state.scene) return null;
    resize();
    const cam = state.camera;
    const { towards, up } = basis(cam);
    const body = {
      server: state.scene.server,
      eye: add(cam.target, scale(towards, cam.distance)), target: cam.target.slice(), up,
      fov: (FOV * 180) / Math.PI, width: canvas.width, height: canvas.height, orthographic: cam.ortho,
    };
    const text = JSON.stringify(body);
    if (text === cameraSent) return null;
    cameraSent = text;
    try {
      const answer = await fetch("/camera", {
        method: "POST", headers: { "Content-Type": "application/json" }, body: text, cache: "no-store" });
      const data = await answer.json().catch(() => ({}));
      return answer.ok ? data.version : null;
    } catch (error) {
      return null;
    }
  }

  function noViewName() {
    for (const name of Object.keys(VIEWS)) $(`view-${name}`).classList.remove("active");
  }

  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    canvas.setPointerCapture(e.pointerId);
    const pan = e.button === 1 || e.button === 2 || e.shiftKey;
    state.drag = { x: e.clientX, y: e.clientY, pan };
    state.pressed = { x: e.clientX, y: e.clientY, source: state.pointedSource };
    $("pointed").hidden = true;
  });
  canvas.addEventListener("pointerup", (e) => {
    const pressed = state.pressed;
    state.pressed = null;
    if (pressed && pressed.source && e.button === 0 &&
        Math.abs(e.clientX - pressed.x) + Math.abs(e.clientY - pressed.y) < 4) {
      copied(pressed.source);  // a click, not a turn of the camera
    }
    if (state.drag && state.drag.moved) cameraStopped();
    state.drag = null;
    canvas.releasePointerCapture(e.pointerId);
    redraw();
  });
  canvas.addEventListener("pointermove", (e) => {
    const rect = canvas.getBoundingClientRect();
    state.pointer = [e.clientX - rect.left, e.clientY - rect.top];
    const drag = state.drag;
    if (!drag) {
      redraw();
      return;
    }
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    drag.moved = true;
    const cam = state.camera;
    if (drag.pan) {
      const { right, up } = basis(cam);
      const perPixel = (2 * cam.distance * Math.tan(FOV / 2)) / Math.max(1, canvas.clientHeight);
      cam.target = add(cam.target, add(scale(right, -dx * perPixel), scale(up, dy * perPixel)));
    } else {
      cam.azimuth -= dx * 0.4;
      cam.elevation = Math.max(-90, Math.min(90, cam.elevation + dy * 0.4));
      noViewName();
    }
    redraw();
  });
  canvas.addEventListener("pointerleave", () => {
    state.pointer = null;
    $("pointed").hidden = true;
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const amount = e.deltaMode === 1 ? e.deltaY * 30 : e.deltaY;
    state.camera.distance *= Math.exp(Math.max(-300, Math.min(300, amount)) * 0.0015);
    redraw();
    cameraStopped();
  }, { passive: false });
  for (const name of Object.keys(VIEWS)) $(`view-${name}`).addEventListener("click", () => setView(name));
  $("view-fit").addEventListener("click", () => fit());
  window.addEventListener("resize", () => {
    redraw();
    cameraStopped();
  });

  // ---- frames of an animation, and the section plane ----
  function showFrame(index) {
    const count = state.frames.length;
    state.current = count ? ((index % count) + count) % count : 0;
    $("frame").value = String(state.current);
    const frame = shown();
    $("frame-label").textContent = frame
      ? `frame ${frame.meta.number} (${state.current + 1}/${count}) · ${frame.meta.where}`
      : "no frame";
    redraw();
  }

  function play(on) {
    if (state.timer) clearInterval(state.timer);
    state.timer = on ? setInterval(() => showFrame(state.current + 1), 125) : null;
    $("play").textContent = on ? "❚❚" : "▶";
    $("play").title = on ? "pause" : "play the frames";
  }

  $("frame").addEventListener("input", (e) => {
    play(false);
    showFrame(Number(e.target.value));
  });
  $("play").addEventListener("click", () => play(!state.timer && state.frames.length > 1));

  function updateSection() {
    const slider = $("section");
    const value = Number(slider.value);
    if (!state.box || value >= Number(slider.max)) {
      state.cut = Infinity;
      $("section-label").textContent = "off";
    } else {
      const [lo, hi] = state.box;
      state.cut = lo[2] + ((hi[2] - lo[2]) * value) / Number(slider.max);
      $("section-label").textContent = `z = ${state.cut.toFixed(2)}`;
    }
    redraw();
  }
  $("section").addEventListener("input", updateSection);

  // ---- the scene from the server ----
  function showDiagnostics(scene) {
    const list = $("diagnostics-list");
    list.replaceChildren();
    let errors = 0, warnings = 0;
    for (const d of scene.diagnostics) {
      if (d.kind === "error") errors++;
      else warnings++;
      const item = document.createElement("li");
      item.className = d.kind;
      const place = d.file ? `${d.file}:${d.line}:${d.column}: ` : "castor: ";
      const kind = document.createElement("span");
      kind.className = "kind";
      kind.textContent = d.kind;
      item.append(place, kind, `: ${d.message}`);
      if (d.text !== null && d.text.length <= 300) {
        const pre = document.createElement("pre");
        pre.textContent = `${d.text}\n${" ".repeat(Math.max(0, (d.column || 1) - 1))}^`;
        item.append(pre);
      }
      list.append(item);
    }
    const words = [];
    if (errors) words.push(`${errors} error${errors > 1 ? "s" : ""}`);
    if (warnings) words.push(`${warnings} warning${warnings > 1 ? "s" : ""}`);
    $("diagnostics-title").textContent = words.join(", ");
    $("diagnostics").hidden = !scene.diagnostics.length;
  }

  // A check box for each layer of the frames (their classes, and "unclassed"):
  // unticked, its faces are neither drawn nor pointed at. Only a scene with
  // classes has layers to show.
  function showLayers(scene) {
    const names = [...new Set(scene.frames.flatMap((f) => f.origins.map(layerOf)))].sort(byLayer);
    const list = $("layers-list");
    const key = names.join(" ");
    if (list.dataset.names !== key) {
      list.dataset.names = key;
      list.replaceChildren();
      for (const name of names) {
        const label = document.createElement("label");
        const box = document.createElement("input");
        box.type = "checkbox";
        box.id = `layer-${name}`;
        box.dataset.layer = name;
        box.checked = !state.hidden.has(name);
        box.addEventListener("change", () => {
          if (box.checked) state.hidden.delete(name);
          else state.hidden.add(name);
          redraw();
        });
        label.append(box, ` ${name}`);
        list.append(label);
      }
    }
    const classed = names.some((name) => name !== UNCLASSED);
    $("layers-toggle").hidden = !classed;
    if (!classed) $("layers").hidden = true;
  }
  $("layers-toggle").addEventListener("click", () => {
    $("layers").hidden = !$("layers").hidden;
    $("layers-toggle").classList.toggle("active", !$("layers").hidden);
  });

  // ``faceting``: what is under way is a refacet for this view, nothing evaluated
  function showStatus(scene, evaluating, faceting) {
    const status = $("status");
    if (!scene) {
      status.textContent = "evaluating…";
      return;
    }
    const count = scene.frames.length;
    const polygons = scene.frames.reduce((s, f) => s + f.polygons, 0);
    let text;
    if (scene.stale) text = `the scene has errors: showing the last good frames`;
    else if (!scene.evaluated) text = "evaluating…";
    else if (!count) text = scene.diagnostics.length ? "no frame" : "no frame: the scene has no '>' command";
    else text = `${count} frame${count > 1 ? "s" : ""} · ${polygons.toLocaleString("en")} polygons${count > 1 ? " in all" : ""} · ` +
      `${scene.seconds.toFixed(2)} s at ${scene.finished}`;
    if (count && scene.refaceted !== null && scene.refaceted !== undefined)
      text += ` · faceted for this view in ${scene.refaceted.toFixed(2)} s`;
    if (evaluating && scene.evaluated) text += faceting ? " · faceting for this view…" : " · evaluating…";
    status.textContent = text;
    status.classList.toggle("stale", !!scene.stale);
  }

  let loading = false, loadAgain = false;
  async function load() {
    if (loading) {
      loadAgain = true;
      return;
    }
    loading = true;
    try {
      do {
        loadAgain = false;
        await loadOnce();
      } while (loadAgain);
      // what is shown once loading settles: its version, and the triangles drawn
      // (every frame's), for whoever checks that the facets follow the view
      if (state.scene) {
        document.body.dataset.triangles = String(state.scene.frames.reduce((s, f) => s + f.triangles, 0));
        document.body.dataset.version = String(state.scene.version);
      }
    } finally {
      loading = false;
    }
  }

  async function loadOnce() {
    const answer = await fetch("/scene.json", { cache: "no-store" });
    if (!answer.ok) return;
    const scene = await answer.json();
    if (state.server !== null && scene.server !== state.server) return; // an event will say
    if (scene.version <= state.version) return;
    const key = scene.frames.map((f) => f.url).join(" ");
    let frames = state.frames;
    if (key !== state.framesKey) {
      const bodies = await Promise.all(scene.frames.map((f) =>
        fetch(f.url, { cache: "no-store" }).then((r) => (r.ok ? r.arrayBuffer() : null))));
      if (bodies.some((b) => b === null)) {
        loadAgain = true; // newer frames came meanwhile
        return;
      }
      frames = gl ? scene.frames.map((meta, i) => ({ meta, mesh: buildMesh(meta, bodies[i]) })) : [];
      for (const old of state.frames) freeMesh(old.mesh);
      state.framesKey = key;
    }
    state.frames = frames;
    state.scene = scene;
    state.version = scene.version;
    let box = null;
    for (const f of scene.frames) {
      if (!f.box) continue;
      box = box ? [box[0].map((v, i) => Math.min(v, f.box[0][i])), box[1].map((v, i) => Math.max(v, f.box[1][i]))]
        : [f.box[0].slice(), f.box[1].slice()];
    }
    state.box = box || state.box;
    $("frame").max = String(Math.max(0, frames.length - 1));
    $("animation").classList.toggle("single", frames.length <= 1);
    showDiagnostics(scene);
    showLayers(scene);
    showStatus(scene, scene.evaluating, scene.faceting);
    updateSection();
    if (!state.fitted && state.box) {
      state.fitted = true;
      fit(false);
    }
    showFrame(state.current);
    draw();
    if (!cameraSent && state.box) {
      // the first frames, faceted with the scene's tolerance: the view's own
      // facets are waited for before the page says it is shown
      clearTimeout(cameraTimer);
      const version = await sendCamera();
      if (version !== null && version !== undefined && version > state.version) loadAgain = true;
    }
  }

  // the view as it is drawn, for editing.js (editing on screen)
  window.castorViewer = {
    canvas, FOV, basis, matrices, radius, redraw, setView,
    camera: () => state.camera,
    frame: () => (shown() ? shown().meta : null),
  };

  if (!gl) $("no-webgl").hidden = false;
  else setView("perspective");
  const events = new EventSource("/events");
  events.addEventListener("scene", (e) => {
    const news = JSON.parse(e.data);
    if (news.server !== state.server) {
      // castor was started again: its versions and frames count from 1 again
      state.server = news.server;
      state.version = -1;
      state.framesKey = "";
      cameraSent = ""; // a new server has not heard the camera
    }
    if (news.version !== state.version) load();
    else showStatus(state.scene, news.evaluating, news.faceting);
  });
  events.addEventListener("error", () => {
    $("status").textContent = "no answer from castor --serve: is it still running?";
  });
  load();
})();

// The parameters panel (castor/serve/parameters.py): a slider for a range, a
// list for choices, a number input otherwise, in their groups. A change sends
// numbers, never text; while a slider is dragged the values go as drafts
// (coarser facets), the value on release as the final one. One request at a
// time: while one is on its way, only the newest value waits behind it.
(function () {
  const $ = (id) => document.getElementById(id);
  let sending = false, waiting = null;

  async function post(body) {
    const answer = await fetch("/parameters", {
      method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body), cache: "no-store" });
    const data = await answer.json().catch(() => ({ error: "no answer" }));
    const error = $("parameters-error");
    error.hidden = answer.ok;
    error.textContent = answer.ok ? "" : data.error;
    return answer.ok ? data : null;
  }

  function send(body) {
    if (sending) {
      waiting = body;
      return;
    }
    sending = true;
    post(body).then((data) => {
      if (data) show(data, body.values === undefined);
    }).finally(() => {
      sending = false;
      if (waiting) {
        const next = waiting;
        waiting = null;
        send(next);
      }
    });
  }

  function control(p) {
    const row = document.createElement("div");
    row.className = "parameter" + (p.changed ? " changed" : "");
    row.title = [p.description, p.location].filter(Boolean).join(" — ");
    const name = document.createElement("span");
    name.className = "name";
    name.textContent = p.name;
    const value = document.createElement("span");
    value.className = "value";
    value.textContent = String(p.value);
    let input;
    const changed = (draft) => {
      // an emptied box (or a number the browser cannot hold, 1e999, which it
      // empties) is no value: nothing is sent until the box holds a number
      if (input.value.trim() === "" || (input.validity && input.validity.badInput)) {
        row.classList.add("invalid");
        return;
      }
      const v = Number(input.value);
      if (!Number.isFinite(v)) return;
      row.classList.remove("invalid");
      value.textContent = String(v);
      row.classList.add("changed");
      send({ values: { [p.name]: v }, draft });
    };
    if (p.control === "slider") {
      input = document.createElement("input");
      input.type = "range";
      input.min = String(p.range.min);
      input.max = String(p.range.max);
      input.step = String(p.range.step);
      input.value = String(p.value);
      input.addEventListener("input", () => changed(true));
      input.addEventListener("change", () => changed(false));
    } else if (p.control === "choice") {
      input = document.createElement("select");
      for (const c of p.choices) {
        const option = document.createElement("option");
        option.value = String(c.value);
        option.textContent = c.label;
        input.appendChild(option);
      }
      input.value = String(p.value);
      input.addEventListener("change", () => changed(false));
    } else {
      input = document.createElement("input");
      input.type = "number";
      input.step = "any";
      input.value = String(p.value);
      input.addEventListener("change", () => changed(false));
    }
    input.id = "parameter-" + p.name;
    input.dataset.name = p.name;
    input.setAttribute("aria-label", p.name);
    row.append(name, input, value);
    return row;
  }

  function show(data, rebuild) {
    $("parameters-toggle").hidden = data.parameters.length === 0;
    $("parameters-command").textContent = data.command;
    const sets = $("parameters-sets");
    while (sets.options.length > 1) sets.remove(1);
    for (const name of data.sets) {
      const option = document.createElement("option");
      option.value = name;
      option.textContent = name;
      sets.appendChild(option);
    }
    sets.title = "sets saved in " + data.sets_file;
    if (!rebuild) return;
    const groups = $("parameters-groups");
    groups.textContent = "";
    let current = undefined;
    for (const p of data.parameters) {
      if (p.group !== current) {
        current = p.group;
        if (current) {
          const title = document.createElement("h3");
          title.textContent = current;
          groups.appendChild(title);
        }
      }
      groups.appendChild(control(p));
    }
  }

  $("parameters-toggle").addEventListener("click", () => {
    $("parameters").hidden = !$("parameters").hidden;
    $("parameters-toggle").classList.toggle("active", !$("parameters").hidden);
  });
  $("parameters-reset").addEventListener("click", () => send({ reset: true }));
  $("parameters-sets").addEventListener("change", (e) => {
    if (e.target.value) send({ set: e.target.value });
  });
  $("parameters-save").addEventListener("click", () => {
    const name = $("parameters-name").value.trim();
    if (name) send({ save: name });
  });
  fetch("/parameters.json", { cache: "no-store" }).then((r) => r.json()).then((d) => show(d, true));
})();
