// lynxsim replay: a small WebGL renderer of MuJoCo's primitives (plane, sphere, capsule,
// ellipsoid, cylinder, box), built for the replay pages lynxsim writes. SI units (m),
// MuJoCo's conventions: quaternions (w, x, y, z), geom sizes as MJCF's, a camera looks
// along the -z axis of its frame with y up. Matrices are column-major (WebGL's order).
"use strict";

const LynxGL = (function () {
  // ---- small linear algebra ------------------------------------------------------------
  function quatToMat3(q) {
    // rows of the rotation matrix of unit quaternion q = (w, x, y, z)
    const [w, x, y, z] = q;
    return [
      1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y),
    ];
  }

  function mulMat3(a, b) {
    // row-major 3x3 product a b
    const out = new Array(9).fill(0);
    for (let i = 0; i < 3; i++)
      for (let j = 0; j < 3; j++)
        for (let k = 0; k < 3; k++) out[3 * i + j] += a[3 * i + k] * b[3 * k + j];
    return out;
  }

  function apply3(m, v) {
    return [
      m[0] * v[0] + m[1] * v[1] + m[2] * v[2],
      m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
      m[6] * v[0] + m[7] * v[1] + m[8] * v[2],
    ];
  }

  function modelMatrix(rot, pos) {
    // column-major 4x4 of a rigid pose: row-major rotation rot, position pos
    return new Float32Array([
      rot[0], rot[3], rot[6], 0, rot[1], rot[4], rot[7], 0, rot[2], rot[5], rot[8], 0,
      pos[0], pos[1], pos[2], 1,
    ]);
  }

  function normalMatrix(rot) {
    // column-major 3x3 of a rotation (its own inverse transpose)
    return new Float32Array([rot[0], rot[3], rot[6], rot[1], rot[4], rot[7], rot[2], rot[5], rot[8]]);
  }

  function mulMat4(a, b) {
    const out = new Float32Array(16);
    for (let c = 0; c < 4; c++)
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
        out[4 * c + r] = s;
      }
    return out;
  }

  function viewMatrix(pos, xmat) {
    // world -> camera; xmat row-major, its columns the camera axes in the world
    const R = xmat;
    const t = [0, 1, 2].map((c) => -(R[c] * pos[0] + R[3 + c] * pos[1] + R[6 + c] * pos[2]));
    return new Float32Array([
      R[0], R[1], R[2], 0, R[3], R[4], R[5], 0, R[6], R[7], R[8], 0, t[0], t[1], t[2], 1,
    ]);
  }

  function projection(camera, aspect, near, far) {
    // MuJoCo's: the vertical extent from fovy (degrees; metres when orthographic)
    const half = camera.orthographic ? camera.fovy / 2 : near * Math.tan((camera.fovy * Math.PI) / 360);
    const w = half * aspect;
    const out = new Float32Array(16);
    if (camera.orthographic) {
      out[0] = 1 / w; out[5] = 1 / half; out[10] = -2 / (far - near);
      out[14] = -(far + near) / (far - near); out[15] = 1;
    } else {
      out[0] = near / w; out[5] = near / half; out[10] = -(far + near) / (far - near);
      out[11] = -1; out[14] = (-2 * far * near) / (far - near);
    }
    return out;
  }

  // ---- meshes of the primitives, in the geom's frame (metres) --------------------------
  const SEG = 32;

  function mesh() { return { p: [], n: [], i: [] }; }

  function ring(m, r, z, nz, scaleN) {
    // one ring of SEG + 1 vertices at height z, normals (cos, sin, nz) * scaleN
    const base = m.p.length / 3;
    for (let k = 0; k <= SEG; k++) {
      const a = (2 * Math.PI * k) / SEG, c = Math.cos(a), s = Math.sin(a);
      m.p.push(r * c, r * s, z);
      m.n.push(c * scaleN, s * scaleN, nz);
    }
    return base;
  }

  function strip(m, a, b) {
    for (let k = 0; k < SEG; k++) m.i.push(a + k, b + k, a + k + 1, a + k + 1, b + k, b + k + 1);
  }

  function disc(m, r, z, nz) {
    const centre = m.p.length / 3;
    m.p.push(0, 0, z); m.n.push(0, 0, nz);
    const rim = ring(m, r, z, nz, 0);
    for (let k = 0; k < SEG; k++) m.i.push(centre, rim + k, rim + k + 1);
  }

  function ellipsoid(rx, ry, rz, zshift, half) {
    // half: 0 whole, +1 upper, -1 lower hemisphere; shifted along z by zshift[half]
    const m = mesh(), stacks = 16;
    const from = half > 0 ? stacks / 2 : 0, to = half < 0 ? stacks / 2 : stacks;
    let prev = -1;
    for (let st = from; st <= to; st++) {
      const phi = -Math.PI / 2 + (Math.PI * st) / stacks, cz = Math.sin(phi), cr = Math.cos(phi);
      const base = m.p.length / 3;
      for (let k = 0; k <= SEG; k++) {
        const a = (2 * Math.PI * k) / SEG, x = cr * Math.cos(a), y = cr * Math.sin(a);
        m.p.push(rx * x, ry * y, rz * cz + zshift);
        const nx = x / rx, ny = y / ry, nz = cz / rz, l = Math.hypot(nx, ny, nz) || 1;
        m.n.push(nx / l, ny / l, nz / l);
      }
      if (prev >= 0) strip(m, prev, base);
      prev = base;
    }
    return m;
  }

  function merge(parts) {
    const m = mesh();
    for (const q of parts) {
      const off = m.p.length / 3;
      m.p.push(...q.p); m.n.push(...q.n); m.i.push(...q.i.map((v) => v + off));
    }
    return m;
  }

  function box(sx, sy, sz) {
    const m = mesh();
    const faces = [
      [0, 1, 2, 1], [0, 1, 2, -1], [1, 2, 0, 1], [1, 2, 0, -1], [2, 0, 1, 1], [2, 0, 1, -1],
    ];
    const s = [sx, sy, sz];
    for (const [a, b, c, sign] of faces) {
      const base = m.p.length / 3;
      for (const [u, v] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        const p = [0, 0, 0], n = [0, 0, 0];
        p[a] = sign * s[a]; p[b] = u * s[b]; p[c] = v * s[c]; n[a] = sign;
        m.p.push(...p); m.n.push(...n);
      }
      m.i.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
    return m;
  }

  function cylinder(r, h) {
    const m = mesh();
    strip(m, ring(m, r, -h, 0, 1), ring(m, r, h, 0, 1));
    disc(m, r, h, 1); disc(m, r, -h, -1);
    return m;
  }

  function capsule(r, h) {
    const side = mesh();
    strip(side, ring(side, r, -h, 0, 1), ring(side, r, h, 0, 1));
    return merge([side, ellipsoid(r, r, r, h, 1), ellipsoid(r, r, r, -h, -1)]);
  }

  function plane(sx, sy) {
    const m = mesh();
    m.p.push(-sx, -sy, 0, sx, -sy, 0, sx, sy, 0, -sx, sy, 0);
    m.n.push(0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1);
    m.i.push(0, 1, 2, 0, 2, 3);
    return m;
  }

  // MuJoCo geom types: 0 plane, 2 sphere, 3 capsule, 4 ellipsoid, 5 cylinder, 6 box
  function primitive(kind, size, infinite) {
    const [a, b, c] = size;
    if (kind === 0) return plane(a > 0 ? a : infinite, b > 0 ? b : infinite);
    if (kind === 2) return ellipsoid(a, a, a, 0, 0);
    if (kind === 3) return capsule(a, b);
    if (kind === 4) return ellipsoid(a, b, c, 0, 0);
    if (kind === 5) return cylinder(a, b);
    if (kind === 6) return box(a, b, c);
    throw new Error("unknown primitive " + kind);
  }

  // ---- the GL side ---------------------------------------------------------------------
  const VERTEX = `
    attribute vec3 aPos; attribute vec3 aNormal;
    uniform mat4 uModel; uniform mat4 uViewProj; uniform mat3 uNormal;
    varying vec3 vNormal; varying vec3 vWorld;
    void main() {
      vec4 w = uModel * vec4(aPos, 1.0);
      vWorld = w.xyz; vNormal = uNormal * aNormal;
      gl_Position = uViewProj * w;
    }`;
  const FRAGMENT = `
    precision mediump float;
    uniform vec4 uColor; uniform vec3 uEye; uniform float uFlat;
    uniform float uGrid;
    varying vec3 vNormal; varying vec3 vWorld;
    void main() {
      if (uFlat > 0.5) { gl_FragColor = uColor; return; }
      vec3 n = normalize(vNormal);
      vec3 toEye = uEye - vWorld;
      if (dot(n, toEye) < 0.0) n = -n;
      vec3 head = normalize(toEye);
      float diffuse = 0.6 * max(dot(n, head), 0.0) + 0.3 * max(dot(n, normalize(vec3(0.3, -0.2, 1.0))), 0.0);
      vec3 rgb = uColor.rgb * (0.3 + diffuse);
      if (uGrid > 0.0) {
        vec2 cell = floor(vWorld.xy / uGrid);
        rgb *= mod(cell.x + cell.y, 2.0) < 0.5 ? 0.85 : 1.15;
      }
      gl_FragColor = vec4(rgb, uColor.a);
    }`;

  function compile(gl, vs, fs) {
    const program = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(program, s);
    }
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
    return program;
  }

  function Renderer(canvas, options) {
    const gl = canvas.getContext("webgl", {
      antialias: !options.flat, preserveDrawingBuffer: true, alpha: false,
    });
    if (!gl) throw new Error("WebGL is not available in this browser");
    this.gl = gl;
    this.program = compile(gl, VERTEX, FRAGMENT);
    this.loc = {};
    for (const n of ["aPos", "aNormal"]) this.loc[n] = gl.getAttribLocation(this.program, n);
    for (const n of ["uModel", "uViewProj", "uNormal", "uColor", "uEye", "uFlat", "uGrid"])
      this.loc[n] = gl.getUniformLocation(this.program, n);
    this.flat = !!options.flat;
  }

  Renderer.prototype.upload = function (m) {
    const gl = this.gl;
    const buffer = (target, array) => {
      const b = gl.createBuffer();
      gl.bindBuffer(target, b);
      gl.bufferData(target, array, gl.STATIC_DRAW);
      return b;
    };
    return {
      p: buffer(gl.ARRAY_BUFFER, new Float32Array(m.p)),
      n: buffer(gl.ARRAY_BUFFER, new Float32Array(m.n)),
      i: buffer(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(m.i)),
      count: m.i.length,
    };
  };

  Renderer.prototype.begin = function (view, proj, eye, background) {
    const gl = this.gl, L = this.loc;
    gl.viewport(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight);
    gl.clearColor(background[0], background[1], background[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(L.uViewProj, false, mulMat4(proj, view));
    gl.uniform3fv(L.uEye, eye);
  };

  Renderer.prototype.draw = function (buffers, model, normal, rgba, grid) {
    const gl = this.gl, L = this.loc;
    const transparent = rgba[3] < 1;
    gl.uniform1f(L.uFlat, this.flat || buffers.count === undefined ? 1 : 0);
    if (transparent) {
      gl.enable(gl.BLEND); gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA); gl.depthMask(false);
    }
    gl.uniformMatrix4fv(L.uModel, false, model);
    gl.uniformMatrix3fv(L.uNormal, false, normal);
    gl.uniform4fv(L.uColor, rgba);
    gl.uniform1f(L.uGrid, grid || 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffers.p);
    gl.enableVertexAttribArray(L.aPos);
    gl.vertexAttribPointer(L.aPos, 3, gl.FLOAT, false, 0, 0);
    if (buffers.n) {
      gl.bindBuffer(gl.ARRAY_BUFFER, buffers.n);
      gl.enableVertexAttribArray(L.aNormal);
      gl.vertexAttribPointer(L.aNormal, 3, gl.FLOAT, false, 0, 0);
    } else {
      gl.disableVertexAttribArray(L.aNormal);
      gl.vertexAttrib3f(L.aNormal, 0, 0, 1);
    }
    if (buffers.count !== undefined) {
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffers.i);
      gl.drawElements(gl.TRIANGLES, buffers.count, gl.UNSIGNED_SHORT, 0);
    } else {
      gl.drawArrays(gl.LINE_STRIP, 0, buffers.lineCount);
    }
    if (transparent) { gl.disable(gl.BLEND); gl.depthMask(true); }
  };

  Renderer.prototype.lineBuffer = function () {
    return { p: this.gl.createBuffer(), lineCount: 0 };
  };

  Renderer.prototype.setLine = function (line, points) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, line.p);
    gl.bufferData(gl.ARRAY_BUFFER, points, gl.DYNAMIC_DRAW);
    line.lineCount = points.length / 3;
  };

  return {
    quatToMat3, mulMat3, apply3, modelMatrix, normalMatrix, viewMatrix, projection,
    primitive, Renderer,
  };
})();
