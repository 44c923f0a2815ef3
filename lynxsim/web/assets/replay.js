// lynxsim replay page: a recorded run scrubbed in time. Reads the JSON in #replay-data
// (written by lynxsim.web.page), draws it with LynxGL, and exposes its state as
// window.lynxsimReplay (time, frame, body poses in the world [m], painted geoms).
// Options in the address's fragment: #camera=NAME&size=WxH&mask=moving&t=SECONDS.
"use strict";

(function () {
  const D = JSON.parse(document.getElementById("replay-data").textContent);
  const decode = (text, Type) => {
    const bin = atob(text), bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  };
  const time = decode(D.time_s, Float64Array);
  const F = time.length, B = D.body_names.length, G = D.geoms.names.length;
  const posQ = decode(D.poses.pos_q, Int16Array), quatQ = decode(D.poses.quat_q, Int16Array);
  const tool = decode(D.tool, Float64Array), toolRef = decode(D.tool_ref, Float64Array);
  const targets = decode(D.targets, Float64Array);
  const M = D.clearance.names.length, clearance = decode(D.clearance.values_m, Float64Array);
  const spans = {
    geom: decode(D.contacts.geom, Int32Array), kind: decode(D.contacts.kind, Int32Array),
    start: decode(D.contacts.start_s, Float64Array), end: decode(D.contacts.end_s, Float64Array),
  };
  const halfFrame = F > 1 ? 0.5 * (time[F - 1] - time[0]) / (F - 1) : 0.0;
  const KIND_COLOURS = ["#e0301e", "#9b59d0", "#d4a017"];
  const PAINT = [0.95, 0.05, 0.05, 1];

  // ---- options from the fragment -------------------------------------------------------
  const options = {};
  for (const part of location.hash.replace(/^#/, "").split("&")) {
    const [k, v] = part.split("=");
    if (k && v !== undefined) options[decodeURIComponent(k)] = decodeURIComponent(v);
  }
  const size = /^(\d{2,4})x(\d{2,4})$/.exec(options.size || "");
  const mask = options.mask === "moving";

  // ---- poses at any time, as lynxsim.web.poses.interpolate_poses -----------------------
  function locate(t) {
    if (F === 1) return [0, 0];
    let lo = 0, hi = F - 1;
    if (!(t > time[0])) return [0, 0];
    if (t >= time[F - 1]) return [F - 2, 1];
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (time[mid] <= t) lo = mid; else hi = mid;
    }
    return [lo, Math.min(1, Math.max(0, (t - time[lo]) / (time[lo + 1] - time[lo])))];
  }

  function unitQuat(frame, b) {
    const o = 4 * (frame * B + b), q = [quatQ[o], quatQ[o + 1], quatQ[o + 2], quatQ[o + 3]];
    const n = Math.hypot(...q) || 1;
    return q.map((v) => v / n);
  }

  function bodyPoses(t) {
    const [i, u] = locate(t), j = Math.min(i + 1, F - 1), out = [];
    for (let b = 0; b < B; b++) {
      const pos = [0, 1, 2].map((c) => {
        const a = D.poses.origin[c] + posQ[3 * (i * B + b) + c] * D.poses.step_m;
        const z = D.poses.origin[c] + posQ[3 * (j * B + b) + c] * D.poses.step_m;
        return (1 - u) * a + u * z;
      });
      const q0 = unitQuat(i, b), q1 = unitQuat(j, b);
      const sign = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3] < 0 ? -1 : 1;
      const q = q0.map((v, c) => (1 - u) * v + u * sign * q1[c]);
      const n = Math.hypot(...q) || 1;
      out.push({ name: D.body_names[b], pos, quat: q.map((v) => v / n) });
    }
    return { frame: u >= 1 ? i + 1 : i, bodies: out };
  }

  function toolAt(t, series) {
    const [i, u] = locate(t), j = Math.min(i + 1, F - 1);
    return [0, 1, 2].map((c) => (1 - u) * series[3 * i + c] + u * series[3 * j + c]);
  }

  function paintedAt(t) {
    const out = new Set();
    for (let e = 0; e < spans.geom.length; e++)
      if (spans.start[e] - halfFrame <= t && t <= spans.end[e] + halfFrame) out.add(spans.geom[e]);
    return out;
  }

  // ---- cameras -------------------------------------------------------------------------
  const cameras = {};
  for (const c of D.cameras) cameras[c.name] = c;
  let camera = cameras[options.camera] ? options.camera : D.default_camera;
  let orbit = null;

  function orbitFrom(c) {
    const f = [-c.xmat[2], -c.xmat[5], -c.xmat[8]];
    const toCentre = [0, 1, 2].map((k) => D.center[k] - c.pos[k]);
    let dist = toCentre[0] * f[0] + toCentre[1] * f[1] + toCentre[2] * f[2];
    if (!(dist > 0.1 * D.extent)) dist = D.extent;
    return {
      target: [0, 1, 2].map((k) => c.pos[k] + dist * f[k]),
      az: Math.atan2(f[1], f[0]), el: Math.asin(Math.max(-1, Math.min(1, f[2]))),
      dist, fovy: c.fovy, orthographic: c.orthographic,
    };
  }

  function orbitCamera(o) {
    const el = Math.max(-1.55, Math.min(1.55, o.el));
    const f = [Math.cos(el) * Math.cos(o.az), Math.cos(el) * Math.sin(o.az), Math.sin(el)];
    const r = [f[1], -f[0], 0], rn = Math.hypot(r[0], r[1]) || 1;
    r[0] /= rn; r[1] /= rn;
    const up = [r[1] * f[2], -r[0] * f[2], r[0] * f[1] - r[1] * f[0]];
    return {
      name: "orbit", pos: o.target.map((v, k) => v - o.dist * f[k]),
      xmat: [r[0], up[0], -f[0], r[1], up[1], -f[1], r[2], up[2], -f[2]],
      fovy: o.fovy, orthographic: o.orthographic,
    };
  }

  const current = () => (orbit ? orbitCamera(orbit) : cameras[camera]);

  // ---- the 3D view ---------------------------------------------------------------------
  const canvas = document.getElementById("view");
  let renderer = null, meshes = [], targetMesh = null, pathLine = null, refLine = null;
  try {
    renderer = new LynxGL.Renderer(canvas, { flat: mask });
    const infinite = 10 * D.extent;
    meshes = D.geoms.kind.map((k, g) => renderer.upload(LynxGL.primitive(k, D.geoms.size[g], infinite)));
    targetMesh = renderer.upload(LynxGL.primitive(2, [0.008, 0, 0], infinite));
    pathLine = renderer.lineBuffer();
    refLine = renderer.lineBuffer();
    renderer.setLine(refLine, new Float32Array(toolRef));
  } catch (err) {
    document.getElementById("view-error").textContent = "The 3D view cannot be drawn here: " + err.message;
  }
  const staticRot = D.geoms.quat.map((q) => LynxGL.quatToMat3(q));

  function resize() {
    if (size) {
      // a view of a fixed size, alone at the window's top left (for pictures of it)
      Object.assign(canvas.style, {
        position: "fixed", left: "0px", top: "0px", zIndex: "10", borderRadius: "0px",
        width: size[1] + "px", height: size[2] + "px",
      });
      canvas.width = +size[1]; canvas.height = +size[2];
      return;
    }
    const ratio = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
      canvas.width = Math.round(w * ratio); canvas.height = Math.round(h * ratio);
    }
  }

  let t = time[0], playing = false, speed = 1, draws = 0, last = null;

  function draw() {
    const poses = bodyPoses(t);
    if (!renderer) return poses;
    resize();
    const c = current(), near = D.znear * D.extent, far = D.zfar * D.extent;
    const view = LynxGL.viewMatrix(c.pos, c.xmat);
    const proj = LynxGL.projection(c, canvas.width / Math.max(1, canvas.height), near, far);
    renderer.begin(view, proj, c.pos, mask ? [0, 0, 0] : [0.12, 0.16, 0.22]);
    const painted = paintedAt(t), rots = poses.bodies.map((b) => LynxGL.quatToMat3(b.quat));
    const order = [...Array(G).keys()].sort((a, b) => D.geoms.rgba[b][3] - D.geoms.rgba[a][3]);
    for (const g of order) {
      const b = D.geoms.body[g];
      let rot = staticRot[g], pos = D.geoms.pos[g];
      if (b >= 0) {
        const off = LynxGL.apply3(rots[b], pos);
        rot = LynxGL.mulMat3(rots[b], rot);
        pos = poses.bodies[b].pos.map((v, k) => v + off[k]);
      }
      // mask: the moving bodies white, what is fixed black (it still hides what is behind it)
      const white = b >= 0 ? [1, 1, 1, 1] : [0, 0, 0, 1];
      const rgba = mask ? white : painted.has(g) ? PAINT : D.geoms.rgba[g];
      const grid = D.geoms.kind[g] === 0 && !mask ? 0.1 : 0;
      renderer.draw(meshes[g], LynxGL.modelMatrix(rot, pos), LynxGL.normalMatrix(rot), rgba, grid);
    }
    if (!mask) {
      const eye = [1, 0, 0, 0, 1, 0, 0, 0, 1], none = LynxGL.normalMatrix(eye);
      for (let m = 0; m < targets.length / 3; m++) {
        const p = [targets[3 * m], targets[3 * m + 1], targets[3 * m + 2]];
        renderer.draw(targetMesh, LynxGL.modelMatrix(eye, p), none, [1, 0.6, 0, 0.8]);
      }
      const [i] = locate(t), upto = Math.min(F, i + 1), points = new Float32Array(3 * (upto + 1));
      points.set(tool.subarray(0, 3 * upto));
      points.set(toolAt(t, tool), 3 * upto);
      renderer.setLine(pathLine, points);
      const identity = LynxGL.modelMatrix(eye, [0, 0, 0]);
      if (document.getElementById("show-ref").checked)
        renderer.draw(refLine, identity, none, [0.75, 0.75, 0.75, 1]);
      renderer.draw(pathLine, identity, none, [0.1, 0.45, 1, 1]);
    }
    draws += 1;
    return poses;
  }

  // ---- charts --------------------------------------------------------------------------
  const timeline = document.getElementById("timeline"), plot = document.getElementById("clearance");
  const x0 = 70;
  const xOf = (cv, s) => x0 + ((cv.width - x0 - 10) * (s - time[0])) / Math.max(1e-9, time[F - 1] - time[0]);
  const tOf = (cv, x) => time[0] + ((x - x0) / (cv.width - x0 - 10)) * (time[F - 1] - time[0]);

  function drawTimeline() {
    const g = timeline.getContext("2d"), w = (timeline.width = timeline.clientWidth), h = timeline.height;
    g.clearRect(0, 0, w, h);
    g.font = "11px sans-serif"; g.fillStyle = "#555";
    ["obstacle", "self", "table"].forEach((label, k) => g.fillText(label, 4, 12 + 13 * k));
    for (let e = 0; e < spans.geom.length; e++) {
      const k = spans.kind[e], a = xOf(timeline, spans.start[e]), z = xOf(timeline, spans.end[e]);
      g.fillStyle = KIND_COLOURS[k];
      g.fillRect(a, 3 + 13 * k, Math.max(2, z - a), 10);
    }
    g.fillStyle = "#111"; g.fillRect(xOf(timeline, t) - 1, 0, 2, h);
  }

  const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"];

  function drawClearance() {
    const g = plot.getContext("2d"), w = (plot.width = plot.clientWidth), h = plot.height;
    g.clearRect(0, 0, w, h);
    g.font = "11px sans-serif";
    if (M === 0) { g.fillStyle = "#555"; g.fillText("no obstacle in the scene", x0, h / 2); return; }
    let lo = 0, hi = 0;
    for (const v of clearance) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    hi = Math.max(hi, lo + 1e-3);
    const yOf = (v) => h - 16 - ((h - 26) * (v - lo)) / (hi - lo);
    g.strokeStyle = "#c33"; g.setLineDash([4, 3]); g.beginPath();
    g.moveTo(x0, yOf(0)); g.lineTo(w - 10, yOf(0)); g.stroke(); g.setLineDash([]);
    g.fillStyle = "#555";
    g.fillText((hi * 1e3).toFixed(0) + " mm", 4, yOf(hi) + 4);
    g.fillText((lo * 1e3).toFixed(0) + " mm", 4, yOf(lo));
    for (let m = 0; m < M; m++) {
      g.strokeStyle = PALETTE[m % PALETTE.length]; g.lineWidth = 1.5; g.beginPath();
      for (let f = 0; f < F; f++) {
        const x = xOf(plot, time[f]), y = yOf(clearance[f * M + m]);
        if (f) g.lineTo(x, y); else g.moveTo(x, y);
      }
      g.stroke();
      g.fillStyle = PALETTE[m % PALETTE.length];
      g.fillText(D.clearance.names[m], x0 + 8 + 90 * m, h - 3);
    }
    g.fillStyle = "#111"; g.fillRect(xOf(plot, t) - 1, 0, 2, h - 14);
  }

  // ---- controls ------------------------------------------------------------------------
  const slider = document.getElementById("time"), clock = document.getElementById("clock");
  const playButton = document.getElementById("play"), speedSelect = document.getElementById("speed");
  const cameraSelect = document.getElementById("camera");
  slider.min = String(time[0]); slider.max = String(time[F - 1]); slider.step = "any";
  for (const name of [...Object.keys(cameras), "orbit"]) {
    const o = document.createElement("option");
    o.value = name; o.textContent = name;
    cameraSelect.appendChild(o);
  }
  cameraSelect.value = camera;

  function update() {
    const poses = draw();
    slider.value = String(t);
    clock.textContent = `t = ${t.toFixed(3)} s of ${time[F - 1].toFixed(3)} s, frame ${poses.frame + 1} of ${F}`;
    drawTimeline(); drawClearance();
    return poses;
  }

  function seek(s) {
    t = Math.min(time[F - 1], Math.max(time[0], Number(s)));
    return update();
  }

  function setPlaying(on) {
    playing = on; last = null;
    playButton.textContent = on ? "Pause" : "Play";
    if (on) {
      if (t >= time[F - 1]) t = time[0];
      requestAnimationFrame(tick);
    }
  }

  function tick(now) {
    if (!playing) return;
    if (last !== null) t += ((now - last) / 1000) * speed;
    last = now;
    if (t >= time[F - 1]) { t = time[F - 1]; setPlaying(false); }
    update();
    if (playing) requestAnimationFrame(tick);
  }

  slider.addEventListener("input", () => { setPlaying(false); seek(slider.value); });
  playButton.addEventListener("click", () => setPlaying(!playing));
  speedSelect.addEventListener("change", () => { speed = Number(speedSelect.value); });
  cameraSelect.addEventListener("change", () => {
    if (cameraSelect.value === "orbit") orbit = orbit || orbitFrom(cameras[camera]);
    else { orbit = null; camera = cameraSelect.value; }
    update();
  });
  document.getElementById("show-ref").addEventListener("change", update);
  for (const cv of [timeline, plot])
    cv.addEventListener("click", (ev) => { setPlaying(false); seek(tOf(cv, ev.offsetX)); });
  window.addEventListener("resize", update);
  document.addEventListener("keydown", (ev) => {
    if (ev.target.tagName === "SELECT" || ev.target === slider) return;
    if (ev.key === " ") { ev.preventDefault(); setPlaying(!playing); }
    const [i, u] = locate(t);
    if (ev.key === "ArrowRight") seek(time[Math.min(F - 1, i + 1)]);
    if (ev.key === "ArrowLeft") seek(time[Math.max(0, u > 0 ? i : i - 1)]);
  });

  // orbit camera: drag to turn, shift-drag or right-drag to pan, wheel to zoom
  let drag = null;
  canvas.addEventListener("contextmenu", (ev) => ev.preventDefault());
  canvas.addEventListener("pointerdown", (ev) => {
    drag = { x: ev.clientX, y: ev.clientY, pan: ev.shiftKey || ev.button === 2 };
    canvas.setPointerCapture(ev.pointerId);
  });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("pointermove", (ev) => {
    if (!drag) return;
    if (!orbit) { orbit = orbitFrom(cameras[camera]); cameraSelect.value = "orbit"; }
    const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
    drag.x = ev.clientX; drag.y = ev.clientY;
    if (drag.pan) {
      const c = orbitCamera(orbit), k = (orbit.orthographic ? orbit.fovy : orbit.dist) * 0.002;
      for (let i = 0; i < 3; i++) orbit.target[i] += k * (-dx * c.xmat[3 * i] + dy * c.xmat[3 * i + 1]);
    } else {
      orbit.az -= dx * 0.005;
      orbit.el = Math.max(-1.55, Math.min(1.55, orbit.el + dy * 0.005));
    }
    update();
  });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    if (!orbit) { orbit = orbitFrom(cameras[camera]); cameraSelect.value = "orbit"; }
    const k = Math.exp(ev.deltaY * 0.001);
    if (orbit.orthographic) orbit.fovy *= k; else orbit.dist *= k;
    update();
  }, { passive: false });

  window.lynxsimReplay = {
    frames: F, start: time[0], end: time[F - 1], poseErrorM: D.pose_error_m,
    seek: (s) => { seek(s); return window.lynxsimReplay.state(); },
    state: () => {
      const poses = bodyPoses(t);
      return {
        time_s: t, frame: poses.frame, playing, speed, draws,
        camera: orbit ? "orbit" : camera, bodies: poses.bodies,
        painted: [...paintedAt(t)].map((g) => D.geoms.names[g]),
      };
    },
  };
  seek(options.t !== undefined && isFinite(Number(options.t)) ? Number(options.t) : time[0]);
})();
