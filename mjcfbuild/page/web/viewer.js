// The mjcfbuild report page: the model simulated by MuJoCo's WebAssembly build and drawn with
// WebGL. Everything it needs is in the scripts loaded before it (no fetch: the page works from
// file://). window.mjcfbuildPage exposes its state to tests and to the curious.
'use strict';
(function () {
  const MODEL = window.MJCFBUILD_MODEL;
  const CFG = MODEL.config;
  const page = (window.mjcfbuildPage = { state: 'loading', error: null });
  const $ = (id) => document.getElementById(id);
  const JOINT = 3, KEY = 24, FREE = 0, SLIDE = 2, HINGE = 3;
  const PLANE = 0, SPHERE = 2, CAPSULE = 3, ELLIPSOID = 4, CYLINDER = 5, BOX = 6, MESH = 7;
  const COLLISION_RGBA = [0.85, 0.42, 0.25, 1];

  function setState(state, message) {
    page.state = state;
    document.body.dataset.state = state;
    $('status').textContent = message;
  }

  function bytes(base64) {
    const text = atob(base64);
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
    return out;
  }

  async function gunzip(data) {
    const stream = new Blob([data]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Uint8Array(await new Response(stream).arrayBuffer());
  }

  async function writeFiles(FS) {
    for (const path of Object.keys(MODEL.files)) {
      const parts = ('model/' + path).split('/');
      let folder = '';
      for (const part of parts.slice(0, -1)) {
        folder += '/' + part;
        if (!FS.analyzePath(folder).exists) FS.mkdir(folder);
      }
      FS.writeFile('/model/' + path, await gunzip(bytes(MODEL.files[path])));
    }
  }

  // ---- matrices (column-major, as WebGL wants them) ----
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function unit(a) { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function lookAt(eye, target) {
    const z = unit(sub(eye, target)), x = unit(cross([0, 0, 1], z)), y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function multiply(a, b) {
    const out = new Array(16).fill(0);
    for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) {
      out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    }
    return out;
  }

  // ---- geometry: triangles with normals, in the geom's frame ----
  function pushTri(out, a, b, c, na, nb, nc) {
    out.push(...a, ...na, ...b, ...nb, ...c, ...nc);
  }
  // A surface of revolution about z from a profile of [radius, z, normal r, normal z] points.
  function revolve(profile, segments) {
    const out = [];
    for (let s = 0; s < segments; s++) {
      const a0 = (2 * Math.PI * s) / segments, a1 = (2 * Math.PI * (s + 1)) / segments;
      const c0 = Math.cos(a0), s0 = Math.sin(a0), c1 = Math.cos(a1), s1 = Math.sin(a1);
      for (let i = 0; i + 1 < profile.length; i++) {
        const [r0, z0, nr0, nz0] = profile[i], [r1, z1, nr1, nz1] = profile[i + 1];
        const p00 = [r0 * c0, r0 * s0, z0], p01 = [r0 * c1, r0 * s1, z0];
        const p10 = [r1 * c0, r1 * s0, z1], p11 = [r1 * c1, r1 * s1, z1];
        const n00 = [nr0 * c0, nr0 * s0, nz0], n01 = [nr0 * c1, nr0 * s1, nz0];
        const n10 = [nr1 * c0, nr1 * s0, nz1], n11 = [nr1 * c1, nr1 * s1, nz1];
        pushTri(out, p00, p10, p11, n00, n10, n11);
        pushTri(out, p00, p11, p01, n00, n11, n01);
      }
    }
    return out;
  }
  function arc(radius, zCentre, from, to, steps) {
    const points = [];
    for (let i = 0; i <= steps; i++) {
      const t = from + ((to - from) * i) / steps;
      points.push([radius * Math.cos(t), zCentre + radius * Math.sin(t), Math.cos(t), Math.sin(t)]);
    }
    return points;
  }
  function sphere(r) { return revolve(arc(r, 0, -Math.PI / 2, Math.PI / 2, 12), 24); }
  function capsule(r, h) {
    return revolve([...arc(r, -h, -Math.PI / 2, 0, 6), ...arc(r, h, 0, Math.PI / 2, 6)], 24);
  }
  function cylinder(r, h) {
    return revolve([[0, -h, 0, -1], [r, -h, 0, -1], [r, -h, 1, 0], [r, h, 1, 0], [r, h, 0, 1], [0, h, 0, 1]], 24);
  }
  function ellipsoid(a, b, c) {
    const out = sphere(1);
    for (let i = 0; i < out.length; i += 6) {
      const n = unit([out[i + 3] / a, out[i + 4] / b, out[i + 5] / c]);
      out[i] *= a; out[i + 1] *= b; out[i + 2] *= c;
      out[i + 3] = n[0]; out[i + 4] = n[1]; out[i + 5] = n[2];
    }
    return out;
  }
  function box(x, y, z) {
    const out = [];
    for (let axis = 0; axis < 3; axis++) for (const sign of [-1, 1]) {
      const u = (axis + 1) % 3, v = (axis + 2) % 3, half = [x, y, z], n = [0, 0, 0];
      n[axis] = sign;
      const corner = (du, dv) => {
        const p = [0, 0, 0];
        p[axis] = sign * half[axis];
        p[u] = du * half[u];
        p[v] = dv * half[v];
        return p;
      };
      const a = corner(-1, -1), b = corner(1, -1), c = corner(1, 1), d = corner(-1, 1);
      if (sign > 0) { pushTri(out, a, b, c, n, n, n); pushTri(out, a, c, d, n, n, n); }
      else { pushTri(out, a, c, b, n, n, n); pushTri(out, a, d, c, n, n, n); }
    }
    return out;
  }
  function plane(x, y) {
    const n = [0, 0, 1];
    return [-x, -y, 0, ...n, x, -y, 0, ...n, x, y, 0, ...n, -x, -y, 0, ...n, x, y, 0, ...n, -x, y, 0, ...n];
  }
  function mesh(model, id) {
    const vert = model.mesh_vert, face = model.mesh_face;
    const v0 = model.mesh_vertadr[id], f0 = model.mesh_faceadr[id], nf = model.mesh_facenum[id];
    const out = [];
    for (let f = f0; f < f0 + nf; f++) {
      const p = [0, 1, 2].map((k) => { const v = 3 * (v0 + face[3 * f + k]); return [vert[v], vert[v + 1], vert[v + 2]]; });
      const n = unit(cross(sub(p[1], p[0]), sub(p[2], p[0])));
      pushTri(out, p[0], p[1], p[2], n, n, n);
    }
    return out;
  }

  // ---- the renderer ----
  const VERTEX = `attribute vec3 position; attribute vec3 normal;
    uniform mat4 view_projection; uniform mat4 world;
    varying vec3 v_normal; varying vec3 v_world;
    void main() { vec4 p = world * vec4(position, 1.0); v_world = p.xyz;
      v_normal = mat3(world) * normal; gl_Position = view_projection * p; }`;
  const FRAGMENT = `precision mediump float;
    uniform vec4 colour; uniform vec3 eye; uniform float checker;
    varying vec3 v_normal; varying vec3 v_world;
    void main() { vec3 n = normalize(v_normal); vec3 c = colour.rgb;
      if (checker > 0.0) { float k = mod(floor(v_world.x / checker) + floor(v_world.y / checker), 2.0);
        c = mix(vec3(0.78, 0.80, 0.83), vec3(0.70, 0.72, 0.76), k); }
      vec3 toEye = normalize(eye - v_world);
      float light = 0.35 + 0.45 * abs(dot(n, toEye)) + 0.25 * max(dot(n, normalize(vec3(0.3, 0.2, 1.0))), 0.0);
      gl_FragColor = vec4(c * min(light, 1.05), colour.a); }`;

  function compile(gl, type, source) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
    return shader;
  }

  function makeRenderer(canvas, model, extent) {
    const gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL');
    const program = gl.createProgram();
    gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, VERTEX));
    gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, FRAGMENT));
    gl.linkProgram(program);
    gl.useProgram(program);
    const at = (name) => gl.getUniformLocation(program, name);
    const position = gl.getAttribLocation(program, 'position'), normal = gl.getAttribLocation(program, 'normal');
    const geoms = [];
    const meshes = new Map();
    for (let g = 0; g < model.ngeom; g++) {
      const type = model.geom_type[g], s = model.geom_size.slice(3 * g, 3 * g + 3);
      let triangles;
      if (type === PLANE) triangles = plane(s[0] || extent * 4, s[1] || extent * 4);
      else if (type === SPHERE) triangles = sphere(s[0]);
      else if (type === CAPSULE) triangles = capsule(s[0], s[1]);
      else if (type === CYLINDER) triangles = cylinder(s[0], s[1]);
      else if (type === ELLIPSOID) triangles = ellipsoid(s[0], s[1], s[2]);
      else if (type === BOX) triangles = box(s[0], s[1], s[2]);
      else if (type === MESH) {
        const id = model.geom_dataid[g];
        if (!meshes.has(id)) meshes.set(id, mesh(model, id));
        triangles = meshes.get(id);
      } else continue; // height fields and SDFs are not drawn
      let rgba = Array.from(model.geom_rgba.slice(4 * g, 4 * g + 4));
      const material = model.geom_matid[g];
      const plain = rgba[0] === 0.5 && rgba[1] === 0.5 && rgba[2] === 0.5 && rgba[3] === 1;
      if (material >= 0 && plain) rgba = Array.from(model.mat_rgba.slice(4 * material, 4 * material + 4));
      const collision = model.geom_contype[g] !== 0 || model.geom_conaffinity[g] !== 0;
      if (collision && model.geom_bodyid[g] !== 0) rgba = COLLISION_RGBA;
      if (rgba[3] === 0) continue;
      const buffer = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(triangles), gl.STATIC_DRAW);
      geoms.push({
        id: g, buffer, count: triangles.length / 6, rgba,
        floor: type === PLANE, world: model.geom_bodyid[g] === 0, collision,
      });
    }
    gl.enable(gl.DEPTH_TEST);
    return function draw(data, camera, show) {
      const width = canvas.clientWidth * devicePixelRatio, height = canvas.clientHeight * devicePixelRatio;
      if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
      gl.viewport(0, 0, canvas.width, canvas.height);
      gl.clearColor(0.93, 0.95, 0.98, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      const ce = Math.cos(camera.elevation), eye = [
        camera.target[0] + camera.distance * ce * Math.cos(camera.azimuth),
        camera.target[1] + camera.distance * ce * Math.sin(camera.azimuth),
        camera.target[2] + camera.distance * Math.sin(camera.elevation)];
      const projection = perspective(Math.PI / 4, canvas.width / Math.max(canvas.height, 1), extent / 50, extent * 100);
      gl.uniformMatrix4fv(at('view_projection'), false, multiply(projection, lookAt(eye, camera.target)));
      gl.uniform3fv(at('eye'), eye);
      const xpos = data.geom_xpos, xmat = data.geom_xmat;
      for (const geom of geoms) {
        if (!geom.world && !(geom.collision ? show.collision : show.visual)) continue;
        const g = geom.id, p = 3 * g, r = 9 * g;
        gl.uniformMatrix4fv(at('world'), false, [
          xmat[r], xmat[r + 3], xmat[r + 6], 0, xmat[r + 1], xmat[r + 4], xmat[r + 7], 0,
          xmat[r + 2], xmat[r + 5], xmat[r + 8], 0, xpos[p], xpos[p + 1], xpos[p + 2], 1]);
        gl.uniform4fv(at('colour'), geom.rgba);
        gl.uniform1f(at('checker'), geom.floor ? Math.max(extent / 4, 0.05) : 0);
        gl.bindBuffer(gl.ARRAY_BUFFER, geom.buffer);
        gl.enableVertexAttribArray(position);
        gl.vertexAttribPointer(position, 3, gl.FLOAT, false, 24, 0);
        gl.enableVertexAttribArray(normal);
        gl.vertexAttribPointer(normal, 3, gl.FLOAT, false, 24, 12);
        gl.drawArrays(gl.TRIANGLES, 0, geom.count);
      }
    };
  }

  // ---- the robot's extent at home, for the camera ----
  function bounds(model, data) {
    const low = [Infinity, Infinity, Infinity], high = [-Infinity, -Infinity, -Infinity];
    for (let g = 0; g < model.ngeom; g++) {
      if (model.geom_bodyid[g] === 0) continue;
      const r = Math.min(model.geom_rbound[g], 1);
      for (let k = 0; k < 3; k++) {
        low[k] = Math.min(low[k], data.geom_xpos[3 * g + k] - r);
        high[k] = Math.max(high[k], data.geom_xpos[3 * g + k] + r);
      }
    }
    if (!isFinite(low[0])) return { centre: [0, 0, 0.5], extent: 1, radius: 1 };
    const centre = [0, 1, 2].map((k) => (low[k] + high[k]) / 2);
    const half = [0, 1, 2].map((k) => Math.max((high[k] - low[k]) / 2, 0.02));
    return { centre, extent: Math.max(...half), radius: Math.hypot(...half) };
  }

  function boot(mujoco) {
    const model = mujoco.MjModel.from_xml_path('/model/' + MODEL.scene);
    const data = new mujoco.MjData(model);
    const name = (type, id) => mujoco.mj_id2name(model, type, id);
    const home = mujoco.mj_name2id(model, KEY, 'home');
    const reset = () => {
      if (home >= 0) mujoco.mj_resetDataKeyframe(model, data, home);
      else mujoco.mj_resetData(model, data);
      mujoco.mj_forward(model, data);
    };
    reset();
    const joints = [];
    let freeBody = -1;
    for (let j = 0; j < model.njnt; j++) {
      const type = model.jnt_type[j];
      if (type === FREE && freeBody < 0) freeBody = model.jnt_bodyid[j];
      if (type !== HINGE && type !== SLIDE) continue;
      // jnt_limited is a byte array that @mujoco/mujoco 3.14 cannot hand to JavaScript; a
      // compiled unlimited joint has the range 0 0.
      const low = model.jnt_range[2 * j], high = model.jnt_range[2 * j + 1];
      const range = low < high ? [low, high]
        : type === HINGE ? [-Math.PI, Math.PI] : [-0.5, 0.5];
      joints.push({ id: j, name: name(JOINT, j), adr: model.jnt_qposadr[j], range });
    }
    const { centre, extent, radius } = bounds(model, data);
    // About as far as the sphere around the robot (geoms by their bounding spheres, which
    // overestimate) needs to fit the view's height (45 degrees).
    const camera = { target: centre, distance: 0.8 * radius / Math.sin(Math.PI / 8), azimuth: -0.75, elevation: 0.35 };
    const show = { visual: true, collision: false };
    const draw = makeRenderer($('view'), model, extent);
    let frame = 0;
    const redraw = () => { if (!frame) frame = requestAnimationFrame(() => { frame = 0; draw(data, camera, show); }); };

    // ---- joint sliders ----
    const sliders = new Map();
    const showValue = (joint, input) => { input.nextElementSibling.textContent = Number(input.value).toFixed(3); };
    const syncSliders = () => {
      for (const joint of joints) {
        const input = sliders.get(joint.name);
        input.value = data.qpos[joint.adr];
        showValue(joint, input);
      }
    };
    for (const joint of joints) {
      const row = document.createElement('label');
      row.className = 'joint';
      const input = document.createElement('input');
      Object.assign(input, { type: 'range', min: joint.range[0], max: joint.range[1], step: 'any' });
      input.dataset.joint = joint.name;
      row.append(Object.assign(document.createElement('span'), { textContent: joint.name }), input,
        Object.assign(document.createElement('output'), {}));
      input.addEventListener('input', () => {
        stopTest();
        data.qpos[joint.adr] = Number(input.value);
        mujoco.mj_forward(model, data);
        showValue(joint, input);
        redraw();
      });
      sliders.set(joint.name, input);
      $('joints').append(row);
    }
    syncSliders();

    // ---- the checks, played step by step in real time ----
    let running = null;
    function stopTest() { if (running) { cancelAnimationFrame(running.frame); running = null; } }
    const passive = new Set(CFG.passive || []);
    const watched = joints.filter((joint) => !passive.has(joint.name));
    const finite = () => data.qpos.every(Number.isFinite) && data.qvel.every(Number.isFinite);
    const warnings = () => {
      // The vector is MjData's own (deleting it aborts the next read); each element read is a
      // copy on the WebAssembly heap, deleted here.
      const stats = data.warning, found = [];
      for (let i = 0; i < stats.size(); i++) {
        const stat = stats.get(i);
        if (stat.number) found.push(i);
        stat.delete();
      }
      return found;
    };
    const tilt = () => Math.acos(Math.max(-1, Math.min(1, data.xmat[9 * freeBody + 8])));
    // What the build's check measured (page/tables.js, written with the report).
    const checked = window.MJCFBUILD_CHECKED || {};
    function report(test, passed, details) {
      const box = $('result');
      if (test === 'hold' && checked.hold) {
        details.summary += `; the build measured ${checked.hold.max_deviation.toPrecision(3)}`;
      }
      if (test === 'stand' && checked.stand && !checked.needs_controller) {
        details.summary += `; the build measured a tilt of ${checked.stand.max_tilt.toFixed(3)} rad`;
      }
      if (test === 'stand' && checked.needs_controller) details.summary += ` (the build's check: ${checked.needs_controller})`;
      box.dataset.test = test;
      box.dataset.status = passed ? 'pass' : 'fail';
      for (const key of Object.keys(details)) box.dataset[key] = details[key];
      box.textContent = (passed ? 'pass: ' : 'FAIL: ') + details.summary;
      box.className = passed ? 'pass' : 'fail';
    }
    function play(test, seconds, begin, stepOnce, finish) {
      stopTest();
      begin();
      const total = Math.round(seconds / model.opt.timestep);
      const state = { step: 0, started: performance.now(), frame: 0, stopped: false };
      running = state;
      $('result').className = 'running';
      $('result').dataset.status = 'running';
      $('result').textContent = test + ': running...';
      const tick = () => {
        if (running !== state) return;
        try { advance(); } catch (error) {
          running = null;
          report(test, false, { summary: `${test} stopped: ${error && error.message ? error.message : error}` });
        }
      };
      const advance = () => {
        // Real time: the steps simulated time has fallen behind the clock by, at least one.
        const elapsed = (performance.now() - state.started) / 1000;
        const due = Math.min(total, Math.max(Math.ceil(elapsed / model.opt.timestep), state.step + 1));
        while (state.step < due && !state.stopped) {
          state.stopped = stepOnce(state.step) === false;
          state.step++;
        }
        draw(data, camera, show);
        syncSliders();
        if (state.step >= total || state.stopped) { running = null; finish(); return; }
        state.frame = requestAnimationFrame(tick);
      };
      state.frame = requestAnimationFrame(tick);
    }
    const tolerance = CFG.hold_tolerance;
    function holdTest() {
      let worst = 0, worstJoint = '', homeQpos;
      play('hold', 1.0, () => { reset(); homeQpos = Array.from(data.qpos); }, () => {
        mujoco.mj_step(model, data);
        for (const joint of watched) {
          const deviation = Math.abs(data.qpos[joint.adr] - homeQpos[joint.adr]);
          if (!(deviation <= worst)) { worst = deviation; worstJoint = joint.name; }
        }
      }, () => report('hold', worst <= tolerance, {
        deviation: worst, tolerance, joint: worstJoint,
        summary: `holding home's ctrl for 1 s, the largest joint deviation is `
          + `${worst.toPrecision(3)}${worstJoint ? ` (${worstJoint})` : ''}; tolerance ${tolerance}`,
      }));
    }
    function floorHeight() {
      for (let g = 0; g < model.ngeom; g++) {
        if (model.geom_bodyid[g] === 0 && model.geom_type[g] === PLANE) return data.geom_xpos[3 * g + 2];
      }
      return 0;
    }
    function standTest() {
      let worst = 0, worstJoint = '', maxTilt = 0, sink = 0, height = 0, homeQpos;
      const begin = () => {
        reset();
        homeQpos = Array.from(data.qpos);
        height = data.xpos[3 * freeBody + 2] - floorHeight();
      };
      play('stand', 5.0, begin, () => {
        mujoco.mj_step(model, data);
        maxTilt = Math.max(maxTilt, tilt());
        sink = Math.max(sink, height - (data.xpos[3 * freeBody + 2] - floorHeight()));
        for (const joint of watched) {
          const deviation = Math.abs(data.qpos[joint.adr] - homeQpos[joint.adr]);
          if (!(deviation <= worst)) { worst = deviation; worstJoint = joint.name; }
        }
        if (!finite()) { maxTilt = Math.PI; return false; }
      }, () => {
        const stands = maxTilt <= 0.2 && sink <= 0.1 * Math.max(height, 0) + 0.01 && worst <= tolerance;
        report('stand', stands, {
          deviation: worst, tolerance, tilt: maxTilt, sink, joint: worstJoint,
          summary: `standing at home for 5 s: base tilted ${maxTilt.toFixed(3)} rad, `
            + `sank ${(sink * 1000).toFixed(0)} mm; largest joint deviation `
            + `${worst.toPrecision(3)}${worstJoint ? ` (${worstJoint})` : ''}; tolerance ${tolerance}`,
        });
      });
    }
    function menagerieTest() {
      const nu = model.nu, centre = [], radius = [];
      for (let a = 0; a < nu; a++) {
        const lo = model.actuator_ctrlrange[2 * a], hi = model.actuator_ctrlrange[2 * a + 1], limited = lo < hi;
        centre.push(limited ? (lo + hi) / 2 : 0);
        radius.push(limited ? (hi - lo) / 2 : 1);
      }
      let ok = true, warned = [];
      play('menagerie', 1.0, () => { mujoco.mj_resetData(model, data); mujoco.mj_forward(model, data); }, (step) => {
        for (let a = 0; a < nu; a++) data.ctrl[a] = centre[a] + radius[a] * (2 * mujoco.mju_Halton(step, a + 2) - 1);
        mujoco.mj_step(model, data);
        if (!finite()) { ok = false; return false; }
        if (step % 50 === 49) { warned = warnings(); if (warned.length) return false; }
      }, () => {
        if (ok) warned = warnings();
        report('menagerie', ok && !warned.length, {
          warnings: warned.length, finite: ok,
          summary: `1 s of pseudorandom control: ${ok ? 'finite' : 'NOT finite'}, ${warned.length} kinds of MuJoCo warning`,
        });
      });
    }

    // ---- controls ----
    $('show-visual').addEventListener('change', (e) => { show.visual = e.target.checked; redraw(); });
    $('show-collision').addEventListener('change', (e) => { show.collision = e.target.checked; redraw(); });
    $('home').addEventListener('click', () => { stopTest(); reset(); syncSliders(); redraw(); });
    $('hold').addEventListener('click', holdTest);
    $('stand').addEventListener('click', standTest);
    $('menagerie').addEventListener('click', menagerieTest);
    $('hold').hidden = home < 0 || freeBody >= 0;
    $('stand').hidden = home < 0 || freeBody < 0;
    $('menagerie').hidden = model.nu === 0;
    const canvas = $('view');
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => {
      drag = { x: e.clientX, y: e.clientY, pan: e.button !== 0 || e.shiftKey };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        const k = camera.distance / canvas.clientHeight, a = camera.azimuth;
        camera.target = [camera.target[0] + k * (dx * Math.sin(a) - dy * Math.cos(a) * Math.sin(camera.elevation)),
          camera.target[1] - k * (dx * Math.cos(a) + dy * Math.sin(a) * Math.sin(camera.elevation)),
          camera.target[2] + k * dy * Math.cos(camera.elevation)];
      } else {
        camera.azimuth -= dx * 0.01;
        camera.elevation = Math.max(-1.5, Math.min(1.5, camera.elevation + dy * 0.01));
      }
      redraw();
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      camera.distance *= Math.exp(e.deltaY * 0.001);
      redraw();
    }, { passive: false });
    window.addEventListener('resize', redraw);

    Object.assign(page, {
      mujoco, model, data, camera, show, joints: joints.map((j) => j.name),
      qpos: (joint) => data.qpos[joints.find((j) => j.name === joint).adr],
      bodyPosition: (body) => {
        const b = mujoco.mj_name2id(model, 1, body);
        return Array.from(data.xpos.slice(3 * b, 3 * b + 3));
      },
      draw: () => draw(data, camera, show),
    });
    draw(data, camera, show);
    const version = mujoco.mj_versionString ? mujoco.mj_versionString() : '';
    setState('ready', `MuJoCo ${version} (WebAssembly): ${model.nbody - 1} bodies, `
      + `${joints.length} joints, ${model.nu} actuators`);
  }

  async function start() {
    if (typeof window.MJCFBUILD_TABLES === 'string') $('report').innerHTML = window.MJCFBUILD_TABLES;
    // mjcfbuild diff --write puts what changed since the base revision above the tables.
    if (typeof window.MJCFBUILD_CHANGES === 'string') {
      $('report').insertAdjacentHTML('afterbegin', '<section id="changes">' + window.MJCFBUILD_CHANGES + '</section>');
    }
    try {
      setState('loading', 'loading MuJoCo...');
      const wasm = await gunzip(bytes(window.MJCFBUILD_WASM));
      const mujoco = await window.loadMujoco({ wasmBinary: wasm });
      await writeFiles(mujoco.FS);
      boot(mujoco);
    } catch (error) {
      console.error(error);
      page.error = String(error && error.message ? error.message : error);
      setState('error', 'the page could not load the model: ' + page.error);
    }
  }
  start();
})();
