// The viewer page's own script, inlined after three.js by report/view_html.cpp (docs/VIEWER.md
// says what it does). The build embeds this file as it is (report/embed_text.cmake); a CTest
// parses it (report/view_script_parse).
(function () {
  'use strict';
  const status = { errors: [] };
  const publish = () => {
    const d = document.body.dataset;
    d.errors = String(status.errors.length);
    if (status.errors.length) d.errorText = status.errors.join(' | ');
  };
  window.addEventListener('error', (e) => { status.errors.push(String(e.message)); publish(); });
  const consoleError = console.error.bind(console);
  console.error = (...args) => { status.errors.push(args.join(' ')); publish(); consoleError(...args); };

  const data = JSON.parse(document.getElementById('vcontact-data').textContent);
  const times = data.times;
  const frames = times.length;
  const palette = [0x8aa1b1, 0xc0504d, 0x4f81bd, 0x9bbb59, 0x8064a2, 0xf79646, 0x4bacc6];
  const pairColors = [0xff3b30, 0x34c759, 0x007aff, 0xff9500, 0xaf52de, 0x00c7be];
  const hex = (c) => '#' + c.toString(16).padStart(6, '0');

  // --- scene -------------------------------------------------------------------------------
  const view = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f6f8);
  const camera = new THREE.PerspectiveCamera(40, 1, 1e-6, 1e3);
  camera.up.set(0, 0, 1);
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  // A light that follows the camera, aimed at the scene's centre (set below).
  const sun = new THREE.DirectionalLight(0xffffff, 0.75);
  camera.add(sun);
  sun.position.set(0.3, 0.6, 1);
  scene.add(camera);
  scene.add(sun.target);

  const poseAt = (body, i) => body.poses.slice(7 * i, 7 * i + 7);
  // Bounds of every bounded body over the whole run, for the camera and the half-spaces.
  const box = new THREE.Box3();
  data.bodies.forEach((b) => {
    if (b.halfspace) return;
    const local = new THREE.Box3().setFromArray(b.vertices);
    const r = local.getSize(new THREE.Vector3()).length() / 2;
    const c = local.getCenter(new THREE.Vector3());
    for (let i = 0; i < frames; i += Math.max(1, Math.floor(frames / 50))) {
      const p = poseAt(b, i);
      const q = new THREE.Quaternion(p[4], p[5], p[6], p[3]);
      const w = c.clone().applyQuaternion(q).add(new THREE.Vector3(p[0], p[1], p[2]));
      box.expandByPoint(w.clone().addScalar(r));
      box.expandByPoint(w.clone().addScalar(-r));
    }
  });
  if (box.isEmpty()) box.set(new THREE.Vector3(-0.05, -0.05, -0.05), new THREE.Vector3(0.05, 0.05, 0.05));
  const center = box.getCenter(new THREE.Vector3());
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-4);
  sun.target.position.copy(center);

  const bodyMeshes = data.bodies.map((b, k) => {
    let geometry;
    if (b.halfspace) {
      geometry = new THREE.PlaneBufferGeometry(6 * radius, 6 * radius);
    } else {
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(b.vertices, 3));
      geometry.setIndex(b.faces);
      geometry.computeVertexNormals();
    }
    // A ghost (a dynamic compare's record) is grey and faint, and does not hide what is behind.
    const material = new THREE.MeshPhongMaterial({
      color: b.ghost ? 0x9e9e9e : palette[k % palette.length], flatShading: !b.halfspace,
      side: THREE.DoubleSide, transparent: true,
      opacity: b.ghost ? 0.3 : b.halfspace ? 0.55 : 0.85, depthWrite: !b.ghost });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.userData.body = b.name;
    if (b.ghost) {
      mesh.renderOrder = 1;
      mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
        new THREE.LineBasicMaterial({ color: 0x616161 })));
    }
    scene.add(mesh);
    return mesh;
  });
  if (bodyMeshes.some((m, k) => data.bodies[k].halfspace)) {
    // A half-space's plane centred under the bodies: its own frame's origin may be far away.
    bodyMeshes.forEach((m, k) => {
      if (!data.bodies[k].halfspace) return;
      const p = poseAt(data.bodies[k], 0);
      const q = new THREE.Quaternion(p[4], p[5], p[6], p[3]);
      const local = center.clone().sub(new THREE.Vector3(p[0], p[1], p[2]))
        .applyQuaternion(q.clone().conjugate());
      m.geometry.translate(local.x, local.y, 0);
    });
  }

  // Contact markers: a sphere at each patch centroid and an arrow along n, as long as f_n is
  // against the largest f_n of the run (up to 0.6 of the scene's radius), drawn over the bodies.
  let maxFn = 0;
  data.pairs.forEach((p) => p.patches.forEach((row) => {
    for (let j = 6; j < row.length; j += 7) maxFn = Math.max(maxFn, Math.abs(row[j]));
  }));
  const markerPool = data.pairs.map(() => []);
  const marker = (k, j) => {
    const pool = markerPool[k];
    while (pool.length <= j) {
      const color = pairColors[k % pairColors.length];
      const dot = new THREE.Mesh(new THREE.SphereBufferGeometry(0.025 * radius, 16, 8),
        new THREE.MeshBasicMaterial({ color: color, depthTest: false }));
      dot.renderOrder = 2;
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, color);
      [arrow.line, arrow.cone].forEach((part) => { part.material.depthTest = false; part.renderOrder = 2; });
      scene.add(dot); scene.add(arrow);
      pool.push({ dot: dot, arrow: arrow });
    }
    return pool[j];
  };

  // Loads and springs (loads.csv): an orange arrow from the point where the force acts, along
  // the force, as long as its magnitude is against the largest of the run's loads.
  let maxLoad = 0;
  data.loads.forEach((l) => {
    for (let j = 0; j < l.rows.length; j += 6)
      maxLoad = Math.max(maxLoad, Math.hypot(l.rows[j + 3], l.rows[j + 4], l.rows[j + 5]));
  });
  const loadArrows = data.loads.map(() => {
    const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, 0xff8c00);
    [arrow.line, arrow.cone].forEach((part) => { part.material.depthTest = false; part.renderOrder = 2; });
    scene.add(arrow);
    return arrow;
  });
  const showLoads = () => {
    let shown = 0;
    data.loads.forEach((l, k) => {
      const r = l.rows.slice(6 * frame, 6 * frame + 6);
      const f = new THREE.Vector3(r[3], r[4], r[5]);
      const size = f.length();
      loadArrows[k].visible = size > 0;
      if (size === 0) return;
      const len = Math.max(0.6 * radius * size / maxLoad, 0.05 * radius);
      loadArrows[k].position.set(r[0], r[1], r[2]);
      loadArrows[k].setDirection(f.normalize());
      loadArrows[k].setLength(len, 0.3 * len, 0.15 * len);
      ++shown;
    });
    document.body.dataset.loads = String(shown);
  };

  let frame = 0;
  const setFrame = (i) => {
    frame = Math.max(0, Math.min(frames - 1, i));
    data.bodies.forEach((b, k) => {
      const p = poseAt(b, frame);
      bodyMeshes[k].position.set(p[0], p[1], p[2]);
      bodyMeshes[k].quaternion.set(p[4], p[5], p[6], p[3]);
    });
    let shown = 0;
    data.pairs.forEach((pair, k) => {
      const row = pair.patches[frame];
      const count = row.length / 7;
      for (let j = 0; j < count; ++j) {
        const m = marker(k, j);
        const c = new THREE.Vector3(row[7 * j], row[7 * j + 1], row[7 * j + 2]);
        const n = new THREE.Vector3(row[7 * j + 3], row[7 * j + 4], row[7 * j + 5]).normalize();
        const len = maxFn > 0 ? Math.max(0.6 * radius * Math.abs(row[7 * j + 6]) / maxFn, 0.05 * radius) : 0.05 * radius;
        m.dot.position.copy(c);
        m.arrow.position.copy(c);
        m.arrow.setDirection(row[7 * j + 6] < 0 ? n.negate() : n);
        m.arrow.setLength(len, 0.3 * len, 0.15 * len);
        m.dot.visible = m.arrow.visible = true;
      }
      markerPool[k].forEach((m, j) => { if (j >= count) m.dot.visible = m.arrow.visible = false; });
      shown += count;
    });
    document.body.dataset.frame = String(frame);
    document.body.dataset.markers = String(shown);
    showLoads();
    slider.value = String(frame);
    clock.textContent = 't = ' + times[frame].toFixed(4) + ' s' +
      (data.trajectory ? ', ' + data.trajectory.phase[frame] : '');
    drawPlot();
  };

  // --- camera: drag to orbit, wheel to zoom, shift-drag to pan --------------------------------
  const orbit = { az: -Math.PI / 3, el: Math.PI / 7, dist: 2.6 * radius, target: center.clone() };
  const placeCamera = () => {
    const e = orbit;
    camera.position.set(e.target.x + e.dist * Math.cos(e.el) * Math.cos(e.az),
      e.target.y + e.dist * Math.cos(e.el) * Math.sin(e.az), e.target.z + e.dist * Math.sin(e.el));
    camera.near = e.dist / 1000; camera.far = e.dist * 100; camera.updateProjectionMatrix();
    camera.lookAt(e.target);
  };
  let drag = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey }; });
  window.addEventListener('pointerup', () => { drag = null; });
  window.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      const right = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 0);
      const up = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 1);
      const s = orbit.dist / view.clientHeight;
      orbit.target.addScaledVector(right, -dx * s).addScaledVector(up, dy * s);
    } else {
      orbit.az -= dx * 0.01;
      orbit.el = Math.max(-1.5, Math.min(1.5, orbit.el + dy * 0.01));
    }
    placeCamera();
  });
  renderer.domElement.addEventListener('wheel', (e) => {
    e.preventDefault();
    orbit.dist *= Math.exp(e.deltaY * 0.001);
    placeCamera();
  }, { passive: false });

  // --- controls ------------------------------------------------------------------------------
  const slider = document.getElementById('slider');
  const clock = document.getElementById('clock');
  const playButton = document.getElementById('play');
  const speed = document.getElementById('speed');
  slider.max = String(frames - 1);
  const duration = times[frames - 1] - times[0];
  [0.001, 0.01, 0.02, 0.05, 0.1, 0.25, 0.5, 1, 2].forEach((s) => {
    const o = document.createElement('option');
    o.value = String(s); o.textContent = s + '×';
    speed.appendChild(o);
  });
  // Default speed: the whole run in about ten seconds of wall time.
  speed.value = String([0.001, 0.01, 0.02, 0.05, 0.1, 0.25, 0.5, 1, 2]
    .reduce((best, s) => Math.abs(Math.log(s * 10 / Math.max(duration, 1e-9))) <
      Math.abs(Math.log(best * 10 / Math.max(duration, 1e-9))) ? s : best, 1));
  let playing = false, simTime = times[0], lastWall = null;
  const setPlaying = (p) => { playing = p; playButton.textContent = p ? 'Pause' : 'Play'; lastWall = null; };
  playButton.addEventListener('click', () => {
    if (!playing && frame === frames - 1) simTime = times[0];
    setPlaying(!playing);
  });
  slider.addEventListener('input', () => { setPlaying(false); setFrame(Number(slider.value)); simTime = times[frame]; });
  const frameAt = (t) => {
    let lo = 0, hi = frames - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (times[mid] <= t) lo = mid; else hi = mid - 1; }
    return lo;
  };

  // --- plot against time: the chosen pair's wrench, or a dynamic compare's heights -----------
  const plot = document.getElementById('plot');
  const pairSelect = document.getElementById('pair');
  const wrench = [['fx', '#d62728'], ['fy', '#2ca02c'], ['fz', '#1f77b4'], ['f_n', '#333333']];
  const plots = data.pairs.map((p) => ({ name: p.name, unit: 'N', series: wrench, values: p.wrench }));
  if (data.trajectory) {
    plots.push({ name: 'height and position error', unit: 'm', values: data.trajectory,
      series: [['z', '#9e9e9e'], ['z_sim', '#1f77b4'], ['dp', '#d62728']],
      mark: data.trajectory.part_time });
  }
  plots.forEach((p, k) => {
    const o = document.createElement('option'); o.value = String(k); o.textContent = p.name;
    pairSelect.appendChild(o);
  });
  pairSelect.addEventListener('change', () => drawPlot());
  function drawPlot() {
    const ctx = plot.getContext('2d');
    const w = plot.width = plot.clientWidth * (window.devicePixelRatio || 1);
    const h = plot.height = plot.clientHeight * (window.devicePixelRatio || 1);
    ctx.clearRect(0, 0, w, h);
    if (!plots.length) return;
    const chosen = plots[Number(pairSelect.value) || 0];
    const series = chosen.series;
    let lo = Infinity, hi = -Infinity;
    series.forEach(([key]) => chosen.values[key].forEach((v) => { lo = Math.min(lo, v); hi = Math.max(hi, v); }));
    if (!(hi > lo)) { hi = lo + 1; }
    const m = { l: 70 * w / plot.clientWidth, r: 10, t: 10, b: 24 * h / plot.clientHeight };
    const X = (t) => m.l + (w - m.l - m.r) * (t - times[0]) / Math.max(duration, 1e-12);
    const Y = (v) => h - m.b - (h - m.t - m.b) * (v - lo) / (hi - lo);
    ctx.font = (12 * w / plot.clientWidth) + 'px sans-serif';
    ctx.strokeStyle = '#999'; ctx.strokeRect(m.l, m.t, w - m.l - m.r, h - m.t - m.b);
    ctx.fillStyle = '#333';
    ctx.fillText(hi.toPrecision(3) + ' ' + chosen.unit, 2, m.t + 10);
    ctx.fillText(lo.toPrecision(3) + ' ' + chosen.unit, 2, h - m.b);
    ctx.fillText(times[0].toFixed(3) + ' s', m.l, h - 4);
    ctx.fillText(times[frames - 1].toFixed(3) + ' s', w - m.r - 60, h - 4);
    if (lo < 0 && hi > 0) { ctx.strokeStyle = '#ccc'; ctx.beginPath(); ctx.moveTo(m.l, Y(0)); ctx.lineTo(w - m.r, Y(0)); ctx.stroke(); }
    series.forEach(([key, color], s) => {
      ctx.strokeStyle = color; ctx.lineWidth = 1.5; ctx.beginPath();
      chosen.values[key].forEach((v, i) => { if (i) ctx.lineTo(X(times[i]), Y(v)); else ctx.moveTo(X(times[i]), Y(v)); });
      ctx.stroke();
      ctx.fillStyle = color; ctx.fillText(key, m.l + 8 + 48 * s * w / plot.clientWidth, m.t + 14);
    });
    if (typeof chosen.mark === 'number') {  // where the simulated path parts from the record
      const x = X(times[0] + chosen.mark);
      ctx.strokeStyle = '#d62728'; ctx.setLineDash([4, 4]);
      ctx.beginPath(); ctx.moveTo(x, m.t); ctx.lineTo(x, h - m.b); ctx.stroke();
      ctx.setLineDash([]); ctx.fillStyle = '#d62728'; ctx.fillText('part', x + 3, h - m.b - 4);
    }
    ctx.strokeStyle = '#000'; ctx.beginPath(); ctx.moveTo(X(times[frame]), m.t); ctx.lineTo(X(times[frame]), h - m.b); ctx.stroke();
  }

  // --- loop ----------------------------------------------------------------------------------
  const resize = () => {
    renderer.setSize(view.clientWidth, view.clientHeight);
    camera.aspect = view.clientWidth / Math.max(view.clientHeight, 1);
    camera.updateProjectionMatrix();
  };
  window.addEventListener('resize', () => { resize(); drawPlot(); });
  const screenPositions = () => bodyMeshes.map((m) => {
    const v = m.position.clone().project(camera);
    return [Math.round((v.x + 1) * view.clientWidth / 2), Math.round((1 - v.y) * view.clientHeight / 2)];
  });
  const render = () => {
    renderer.render(scene, camera);
    document.body.dataset.screen = JSON.stringify(screenPositions());
  };
  const tick = (wall) => {
    if (playing) {
      if (lastWall !== null) simTime += (wall - lastWall) / 1000 * Number(speed.value);
      lastWall = wall;
      if (simTime >= times[frames - 1]) { simTime = times[frames - 1]; setPlaying(false); }
      setFrame(frameAt(simTime));
    }
    render();
    requestAnimationFrame(tick);
  };

  document.getElementById('title').textContent = data.scenario + (data.description ? ': ' + data.description : '');
  resize();
  placeCamera();
  // "#t=0.1" opens the page paused at that time (for links and screenshots); otherwise it plays.
  const hashTime = /t=([-+0-9.eE]+)/.exec(window.location.hash);
  setFrame(hashTime ? frameAt(Number(hashTime[1])) : 0);
  simTime = times[frame];
  setPlaying(!hashTime);
  render();
  let meshes = 0;
  scene.traverse((o) => { if (o.isMesh && o.userData.body !== undefined) ++meshes; });
  document.body.dataset.bodyMeshes = String(meshes);
  document.body.dataset.frames = String(frames);
  document.body.dataset.ready = '1';
  publish();
  requestAnimationFrame(tick);
})();
