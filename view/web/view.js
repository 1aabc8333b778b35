/*
 * servoloop view — the 3D part of the page.
 *
 * Connects to the servoloop view server (WebSocket at /ws, JSON messages), builds a
 * three.js scene from the "scene" message (links, joints and visuals taken from each
 * robot's URDF) and moves the link frames from the "frame" messages (model base pose
 * + joint positions). The side panel (controllers, world controls, joint plot,
 * warnings) lives in panel.js, loaded before this file, and is reached through
 * window.servoloopPanel.
 *
 * three.js hierarchy, one per model:
 *   modelsRoot -> model group (base pose from the frame)
 *     -> root link frame -> joint "origin" group (fixed URDF joint origin)
 *        -> joint "motion" group = child link frame (rotation/translation from q) -> ...
 * A link's visuals hang under its frame, each under a group holding the visual origin.
 *
 * Rendering happens in requestAnimationFrame and only when something changed
 * (new frame, camera move, mesh loaded, resize, toggles).
 */
(function () {
  'use strict';

  var panel = window.servoloopPanel;   // UI side panel (panel.js)

  // State exposed for tests; updated in place. ready = a scene and a frame have
  // arrived and no mesh is still loading.
  var view = window.servoloopView = {
    frames: 0, lastFrame: null, scene: null, controllers: null,
    meshesPending: 0, meshFailures: 0, ready: false,
    connected: false, control: false,
    linkPose: linkPose          // (ns, link) -> {xyz, quat} in the world, for tests
  };

  function $(id) { return document.getElementById(id); }
  function updateReady() {
    view.ready = !!(view.scene && view.frames > 0 && view.meshesPending === 0);
  }

  // ------------------------------------------------------------------ renderer

  var needsRender = true;
  function requestRender() { needsRender = true; }

  var scene3 = new THREE.Scene();
  scene3.background = new THREE.Color(0xe6e8eb);
  view.scene3 = scene3;         // the three.js scene, for inspection from the console

  var camera = new THREE.PerspectiveCamera(45, window.innerWidth / window.innerHeight, 0.01, 1000);
  camera.up.set(0, 0, 1);                 // world is Z-up (URDF); set before OrbitControls
  camera.position.set(2.5, -3, 1.8);
  view.camera = camera;         // for inspection from the console

  var renderer = null;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(window.innerWidth, window.innerHeight);
    $('viewport').appendChild(renderer.domElement);
  } catch (e) {
    renderer = null;
    panel.addWarning('WebGL is not available in this browser (' + e.message + '); no 3D view');
  }

  var controls = new THREE.OrbitControls(camera, renderer ? renderer.domElement : $('viewport'));
  controls.target.set(0, 0, 0.5);
  controls.screenSpacePanning = true;     // pan in the screen plane, natural with Z-up
  controls.addEventListener('change', requestRender);
  var userMovedCamera = false;            // once true, scene changes no longer refit the camera
  controls.addEventListener('start', function () { userMovedCamera = true; });
  controls.update();

  scene3.add(new THREE.AmbientLight(0xffffff, 0.4));
  var sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(3, -4, 6);
  scene3.add(sun);
  var fill = new THREE.DirectionalLight(0xffffff, 0.2);
  fill.position.set(-3, 4, 2);
  scene3.add(fill);

  // Ground grid in the XY plane (z = 0), 10 m across in 0.5 m cells, the
  // axes darker; shown always, as a reference. Every line is made of
  // cell-long segments: a 10 m line that passes behind a close camera is
  // dropped whole by some software renderers (Chromium's SwiftShader).
  var grid = (function () {
    var half = 5, cell = 0.5, minor = [], axis = [];
    for (var i = -half; i <= half + 1e-9; i += cell) {
      var target = Math.abs(i) < 1e-9 ? axis : minor;
      for (var j = -half; j < half - 1e-9; j += cell) {
        target.push(i, j, 0, i, j + cell, 0);   // along y
        target.push(j, i, 0, j + cell, i, 0);   // along x
      }
    }
    var group = new THREE.Group();
    [[minor, 0xa9aeb5], [axis, 0x5f646c]].forEach(function (lines) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(lines[0], 3));
      group.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: lines[1] })));
    });
    return group;
  })();
  scene3.add(grid);

  var modelsRoot = new THREE.Group();
  scene3.add(modelsRoot);

  // Textures referenced by COLLADA/MTL files arrive later through the default manager.
  THREE.DefaultLoadingManager.onLoad = requestRender;

  // Keep the scene centred in the part of the window the side panel does not cover.
  var visibleAspect = camera.aspect;
  function onResize() {
    var w = window.innerWidth, h = window.innerHeight;
    var side = $('panel') ? $('panel').offsetWidth : 0;
    if (side > w / 2) side = 0;
    visibleAspect = (w - side) / h;
    camera.setViewOffset(w, h, side / 2, 0, w, h);   // also sets aspect = w / h
    camera.updateProjectionMatrix();
    if (renderer) renderer.setSize(w, h);
    requestRender();
  }
  window.addEventListener('resize', onResize);
  onResize();

  // ------------------------------------------------------------- scene building

  var models = {};        // ns -> built model (see buildModel)
  var axesList = [];      // AxesHelpers at every link frame (shown by #frames-toggle)
  var buildId = 0;        // increases with every rebuild; late mesh loads of older builds are dropped
  var sceneKey = null;    // models of the built scene, to skip rebuilding an identical scene
  var euler = new THREE.Euler(0, 0, 0, 'ZYX');

  // One shared axes geometry/material for all link frames (0.1 m), drawn on top of the
  // visuals since most frames sit inside their link's geometry.
  var axesProto = new THREE.AxesHelper(0.1);
  axesProto.material.depthTest = false;

  // URDF origin: xyz + rpy, fixed axes, R = Rz(yaw)*Ry(pitch)*Rx(roll) = three's 'ZYX' order.
  function setOrigin(obj, origin) {
    var xyz = (origin && origin.xyz) || [0, 0, 0];
    var rpy = (origin && origin.rpy) || [0, 0, 0];
    obj.position.set(xyz[0], xyz[1], xyz[2]);
    euler.set(rpy[0], rpy[1], rpy[2], 'ZYX');
    obj.quaternion.setFromEuler(euler);
  }

  function colorMaterial(rgba) {
    var c = rgba || [0.7, 0.7, 0.7, 1];
    var a = c.length > 3 ? c[3] : 1;
    return new THREE.MeshPhongMaterial({
      color: new THREE.Color(c[0], c[1], c[2]), opacity: a, transparent: a < 1, shininess: 30
    });
  }

  // Collisions drawn in place of a mesh that could not be loaded.
  function fallbackMaterial() {
    return new THREE.MeshPhongMaterial({ color: 0x8a8a8a, opacity: 0.5, transparent: true, depthWrite: false });
  }

  function primitiveGeometry(g) {
    switch (g.type) {
      case 'box':
        return new THREE.BoxBufferGeometry(g.size[0], g.size[1], g.size[2]);
      case 'cylinder': {
        // URDF cylinders run along local Z, three's along Y: turn Y into Z.
        var geo = new THREE.CylinderBufferGeometry(g.radius, g.radius, g.length, 32);
        geo.rotateX(Math.PI / 2);
        return geo;
      }
      case 'sphere':
        return new THREE.SphereBufferGeometry(g.radius, 32, 16);
    }
    return null;
  }

  // Frees GPU resources of a removed subtree (shared axes geometry excepted).
  function disposeTree(root) {
    var seen = new Set();
    root.traverse(function (o) {
      if (o.userData.shared) return;
      if (o.geometry && !seen.has(o.geometry)) { seen.add(o.geometry); o.geometry.dispose(); }
      var mats = Array.isArray(o.material) ? o.material : (o.material ? [o.material] : []);
      mats.forEach(function (m) {
        if (seen.has(m)) return;
        seen.add(m);
        ['map', 'normalMap', 'specularMap', 'emissiveMap', 'bumpMap', 'alphaMap', 'aoMap', 'lightMap']
          .forEach(function (k) { if (m[k]) m[k].dispose(); });
        m.dispose();
      });
    });
  }

  // Builds one model: link frames nested by joints, visuals, q -> joint mapping.
  function buildModel(def, id) {
    var m = { def: def, group: new THREE.Group(), links: {}, joints: {}, qJoints: [] };
    m.group.name = def.ns;

    function linkFrame(name) {
      if (!m.links[name]) {
        var g = new THREE.Group();
        g.name = name;
        var axes = new THREE.LineSegments(axesProto.geometry, axesProto.material);
        axes.userData.shared = true;
        axes.renderOrder = 10;
        axes.visible = false;
        axesList.push(axes);
        g.add(axes);
        m.links[name] = g;
      }
      return m.links[name];
    }
    (def.links || []).forEach(function (l) { linkFrame(l.name); });

    (def.joints || []).forEach(function (j) {
      var parent = linkFrame(j.parent), child = linkFrame(j.child);
      // Guard against malformed trees: a link with two parents or a loop.
      for (var p = parent; p; p = p.parent) {
        if (p === child) { panel.addWarning(def.ns + ': joint ' + j.name + ' closes a loop; ignored'); return; }
      }
      if (child.parent) { panel.addWarning(def.ns + ': link ' + j.child + ' has two parents; joint ' + j.name + ' ignored'); return; }
      var origin = new THREE.Group();
      origin.name = j.name + '/origin';
      setOrigin(origin, j.origin);
      parent.add(origin);
      origin.add(child);                  // the child link frame is the joint's motion group
      var axis = new THREE.Vector3().fromArray(j.axis || [1, 0, 0]);
      if (axis.lengthSq() === 0) axis.set(1, 0, 0);
      m.joints[j.name] = { type: j.type, axis: axis.normalize(), motion: child };
    });

    // Root links (not the child of any joint) sit at the model base pose.
    Object.keys(m.links).forEach(function (name) {
      if (!m.links[name].parent) m.group.add(m.links[name]);
    });
    m.qJoints = (def.joint_names || []).map(function (n) { return m.joints[n] || null; });

    (def.links || []).forEach(function (l) {
      var ctx = { id: id, model: def, link: l, frame: m.links[l.name], fellBack: false };
      (l.visuals || []).forEach(function (v) { addVisual(v, ctx, false); });
    });
    return m;
  }

  // Adds one URDF visual (or collision, when fallback) under its link frame.
  function addVisual(v, ctx, fallback) {
    var holder = new THREE.Group();
    setOrigin(holder, v.origin);
    ctx.frame.add(holder);
    var g = v.geometry || {};
    if (g.type === 'mesh') { loadMesh(g, v.color, holder, ctx, fallback); return; }
    var geo = primitiveGeometry(g);
    if (!geo) {
      panel.addWarning(ctx.model.ns + ': link ' + ctx.link.name + ' has unsupported geometry "' + g.type + '"');
      return;
    }
    holder.add(new THREE.Mesh(geo, fallback ? fallbackMaterial() : colorMaterial(v.color)));
  }

  // A mesh that failed: warn, and draw the link's collisions instead (once per link).
  function meshFailed(ctx, url, why, fallback) {
    view.meshFailures++;
    var where = 'link "' + ctx.link.name + '" of ' + ctx.model.ns;
    if (fallback) {
      panel.addWarning('collision mesh ' + url + ' of ' + where + ' failed to load (' + why + ')');
      return;
    }
    var cols = ctx.link.collisions || [];
    panel.addWarning('mesh ' + url + ' of ' + where + ' failed to load (' + why + '); ' +
                     (cols.length ? 'showing its collision shapes' : 'it has no collision shapes to show'));
    if (!ctx.fellBack) {
      ctx.fellBack = true;
      cols.forEach(function (c) { addVisual(c, ctx, true); });
    }
  }

  // Raw mesh data by URL, shared by all visuals using the same file. Cleared on reconnect.
  var rawCache = new Map();
  function fetchData(url, binary) {
    var key = (binary ? 'b:' : 't:') + url;
    var p = rawCache.get(key);
    if (!p) {
      p = fetch(url).then(function (r) {
        if (!r.ok) throw new Error('HTTP ' + r.status);
        return binary ? r.arrayBuffer() : r.text();
      });
      rawCache.set(key, p);
      p.catch(function () { rawCache.delete(key); });   // retry failures next time
    }
    return p;
  }

  function hasTriangles(root) {
    var found = false;
    root.traverse(function (o) {
      if (o.isMesh && o.geometry && o.geometry.attributes && o.geometry.attributes.position &&
          o.geometry.attributes.position.count > 0) found = true;
    });
    return found;
  }

  // Shading needs normals; files without them (or STLs with zero facet normals) get computed ones.
  function ensureNormals(root, always) {
    root.traverse(function (o) {
      if (o.isMesh && o.geometry && o.geometry.isBufferGeometry &&
          (always || !o.geometry.attributes.normal)) o.geometry.computeVertexNormals();
    });
    return root;
  }

  function replaceMaterials(root, material) {
    root.traverse(function (o) {
      if (!o.isMesh) return;
      (Array.isArray(o.material) ? o.material : [o.material]).forEach(function (m) { if (m) m.dispose(); });
      o.material = material;
    });
  }

  // Parses fetched mesh data into an Object3D (Promise). Throws/rejects on bad data.
  function parseMesh(fmt, data, url, color, fallback) {
    var material = function () { return fallback ? fallbackMaterial() : colorMaterial(color); };
    var abs = new URL(url, location.href).href;
    var base = abs.slice(0, abs.lastIndexOf('/') + 1);
    if (fmt === 'stl') {
      var geo = new THREE.STLLoader().parse(data);
      var obj = new THREE.Mesh(geo, material());
      if (!hasTriangles(obj)) { geo.dispose(); throw new Error('no triangles'); }
      return Promise.resolve(ensureNormals(obj, true));   // STL triangles are flat: face normals
    }
    if (fmt === 'dae') {
      var dae = new THREE.ColladaLoader().parse(data, base);
      if (!dae || !dae.scene || !hasTriangles(dae.scene)) throw new Error('not a usable COLLADA file');
      ensureNormals(dae.scene, false);
      // A COLLADA file exported with its lamps and cameras would light the
      // whole world (ten meshes, ten lamps): only its geometry is drawn, as
      // rviz does.
      var extras = [];
      dae.scene.traverse(function (o) { if (o.isLight || o.isCamera) extras.push(o); });
      extras.forEach(function (o) { o.parent.remove(o); });
      if (fallback) replaceMaterials(dae.scene, material());
      // ColladaLoader turns Z_UP files into Y_UP; our world is Z-up, so turn it back.
      var up = new THREE.Group();
      up.rotation.x = Math.PI / 2;
      up.add(dae.scene);
      return Promise.resolve(up);
    }
    // OBJ, with its material library when it names one (resolved against the OBJ's URL).
    var lib = /^\s*mtllib\s+(.+?)\s*$/m.exec(data);
    var mtlUrl = lib && !fallback ? new URL(lib[1], abs).href : null;
    var mtl = mtlUrl ? fetchData(mtlUrl, false).catch(function (e) {
      panel.addWarning('material library ' + mtlUrl + ' of ' + url + ' failed to load (' + e.message +
                       '); using the URDF colour');
      return null;
    }) : Promise.resolve(null);
    return mtl.then(function (mtlText) {
      var loader = new THREE.OBJLoader();
      if (mtlText !== null) {
        var creator = new THREE.MTLLoader().parse(mtlText, mtlUrl.slice(0, mtlUrl.lastIndexOf('/') + 1));
        creator.preload();
        loader.setMaterials(creator);
      }
      var group = loader.parse(data);
      if (!hasTriangles(group)) throw new Error('no triangles');
      ensureNormals(group, false);
      if (mtlText === null) replaceMaterials(group, material());
      return group;
    });
  }

  // Loads a mesh visual asynchronously into holder (scaled by the URDF scale).
  function loadMesh(g, color, holder, ctx, fallback) {
    var url = g.url, fmt = String(g.format || '').toLowerCase();
    var scaled = new THREE.Group();
    var s = g.scale || [1, 1, 1];
    scaled.scale.set(s[0], s[1], s[2]);
    holder.add(scaled);
    if (fmt !== 'stl' && fmt !== 'dae' && fmt !== 'obj') {
      meshFailed(ctx, url, 'format "' + g.format + '" is not supported by the page', fallback);
      return;
    }
    view.meshesPending++;
    updateReady();
    fetchData(url, fmt === 'stl').then(function (data) {
      return parseMesh(fmt, data, url, color, fallback);
    }).then(function (obj) {
      if (ctx.id !== buildId) { disposeTree(obj); return; }   // scene rebuilt meanwhile
      scaled.add(obj);
    }).catch(function (e) {
      if (ctx.id === buildId) meshFailed(ctx, url, (e && e.message) || String(e), fallback);
    }).then(function () {
      view.meshesPending--;
      updateReady();
      // Meshes change the scene's extent: refit once all are in, unless the user took over.
      if (view.meshesPending === 0 && !userMovedCamera) fitPending = true;
      requestRender();
    });
  }

  function onScene(msg) {
    view.scene = msg;
    grid.visible = true;
    var key = JSON.stringify(msg.models || []);
    if (key !== sceneKey) {
      sceneKey = key;
      buildId++;
      view.meshFailures = 0;           // counts the failures of the current scene
      modelsRoot.children.slice().forEach(function (c) { modelsRoot.remove(c); disposeTree(c); });
      models = {};
      axesList = [];
      (msg.models || []).forEach(function (def) {
        var m = buildModel(def, buildId);
        models[def.ns] = m;
        modelsRoot.add(m.group);
      });
      setAxesVisible($('frames-toggle').checked);
      // Fit the camera after the first frame of this scene, unless the user moved it.
      frameApplied = false;
      if (!cameraFitted || !userMovedCamera) fitPending = true;
      panel.setScene(msg);
    }
    updateReady();
    requestRender();
  }

  function setAxesVisible(on) {
    axesList.forEach(function (a) { a.visible = on; });
    requestRender();
  }
  $('frames-toggle').addEventListener('change', function (e) { setAxesVisible(e.target.checked); });

  // ----------------------------------------------------------------- kinematics

  var latestFrame = null;   // newest frame not yet applied to the scene (applied in animate)
  var frameApplied = false; // a frame has been applied since the last rebuild

  function onFrame(msg) {
    view.frames++;
    view.lastFrame = msg;
    latestFrame = msg;
    panel.recordFrame(msg);
    updateReady();
  }

  // Base pose and joint motions from a frame. A frame older than the built scene (lower
  // generation) only updates the HUD; otherwise models match by ns and q is applied up to
  // the shorter of q and joint_names (joints not listed stay at 0).
  function applyFrame(f) {
    var stale = view.scene && typeof f.generation === 'number' && f.generation < view.scene.generation;
    if (!stale) {
      (f.models || []).forEach(function (fm) {
        var m = models[fm.ns];
        if (!m) return;
        var p = fm.pose;
        if (p && p.length === 7) {
          m.group.position.set(p[0], p[1], p[2]);
          m.group.quaternion.set(p[3], p[4], p[5], p[6]).normalize();
        }
        var q = fm.q || [];
        for (var i = 0; i < m.qJoints.length && i < q.length; i++) {
          var j = m.qJoints[i];
          if (!j || typeof q[i] !== 'number') continue;
          if (j.type === 'revolute' || j.type === 'continuous') j.motion.quaternion.setFromAxisAngle(j.axis, q[i]);
          else if (j.type === 'prismatic') j.motion.position.copy(j.axis).multiplyScalar(q[i]);
        }
      });
    }
    updateHud(f);
  }

  var hud = { time: $('sim-time'), rtf: $('rtf'), paused: $('paused'), steps: $('steps') };
  function updateHud(f) {
    hud.time.textContent = typeof f.t === 'number' ? f.t.toFixed(3) : '-';
    hud.rtf.textContent = typeof f.rtf === 'number' ? f.rtf.toFixed(2) : '-';
    hud.paused.hidden = !f.paused;
    if (hud.steps) hud.steps.textContent = typeof f.steps === 'number' ? String(f.steps) : '-';
  }

  // World pose of a link frame (tests): {xyz:[..], quat:[x,y,z,w]} or null.
  function linkPose(ns, link) {
    var m = models[ns];
    var o = m && m.links[link];
    if (!o) return null;
    o.updateWorldMatrix(true, false);
    var pos = new THREE.Vector3(), quat = new THREE.Quaternion(), scl = new THREE.Vector3();
    o.matrixWorld.decompose(pos, quat, scl);
    return { xyz: pos.toArray(), quat: quat.toArray() };
  }

  // ------------------------------------------------------------------ camera fit

  var fitPending = false, cameraFitted = false;
  var box = new THREE.Box3(), meshBox = new THREE.Box3(), sphere = new THREE.Sphere();
  var viewDir = new THREE.Vector3(1, -1.25, 0.8).normalize();

  // Frames the bounding box of all drawn models (visible meshes) from the front-right, above.
  function fitCamera() {
    modelsRoot.updateMatrixWorld(true);
    box.makeEmpty();
    modelsRoot.traverse(function (o) {
      if (!o.isMesh || !o.geometry) return;
      if (!o.geometry.boundingBox) o.geometry.computeBoundingBox();
      meshBox.copy(o.geometry.boundingBox).applyMatrix4(o.matrixWorld);
      box.union(meshBox);
    });
    if (box.isEmpty()) return;
    box.getBoundingSphere(sphere);
    var r = Math.max(sphere.radius, 0.1);
    var vfov = camera.fov * Math.PI / 180;
    var hfov = 2 * Math.atan(Math.tan(vfov / 2) * visibleAspect);
    var dist = r / Math.sin(Math.min(vfov, hfov) / 2) * 1.2;   // a little margin
    controls.target.copy(sphere.center);
    camera.position.copy(sphere.center).addScaledVector(viewDir, dist);
    camera.near = Math.max(dist / 200, 0.001);
    camera.far = dist * 200;
    camera.updateProjectionMatrix();
    controls.update();
    cameraFitted = true;
    requestRender();
  }

  // --------------------------------------------------------------------- socket

  var socket = null;
  var nextOpId = 1;
  var pendingOps = {};     // id -> {op, button, timer}

  function connect() {
    var ws;
    try {
      ws = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/ws');
    } catch (e) {
      setTimeout(connect, 1000);
      return;
    }
    socket = ws;
    ws.onopen = function () {
      view.connected = true;
      rawCache.clear();                 // a (re)started server may serve other files
      panel.setStatus(true);
    };
    ws.onmessage = function (ev) {
      var msg;
      try { msg = JSON.parse(ev.data); } catch (e) { return; }
      handle(msg);
    };
    ws.onclose = function () {
      socket = null;
      view.connected = false;
      panel.setStatus(false);
      Object.keys(pendingOps).forEach(function (id) { finishOp(id); });
      setTimeout(connect, 1000);        // retry every second
    };
  }

  function handle(msg) {
    switch (msg.type) {
      case 'hello':
        view.control = !!msg.control;
        panel.setControl(view.control);
        break;
      case 'scene': onScene(msg); break;
      case 'frame': onFrame(msg); break;
      case 'controllers':
        view.controllers = msg;
        panel.setControllers(msg);
        break;
      case 'reply': {
        var p = finishOp(msg.id);
        if (!msg.ok) panel.addWarning((p ? p.op : 'request') + ' failed: ' + (msg.error || 'no reason given'));
        break;
      }
      case 'warning': panel.addWarning(String(msg.text)); break;
    }
  }

  function finishOp(id) {
    var p = pendingOps[id];
    if (!p) return null;
    delete pendingOps[id];
    clearTimeout(p.timer);
    if (p.button) p.button.disabled = false;
    return p;
  }

  // Sends a request (only with control); the button stays disabled until the reply.
  function sendOp(msg, button) {
    if (!view.control) return;
    if (!socket || socket.readyState !== WebSocket.OPEN) {
      panel.addWarning(msg.op + ': not connected to the server');
      return;
    }
    msg.id = nextOpId++;
    var p = { op: msg.op, button: button || null };
    p.timer = setTimeout(function () {
      if (finishOp(msg.id)) panel.addWarning(msg.op + ': no reply from the server');
    }, 10000);
    pendingOps[msg.id] = p;
    if (button) button.disabled = true;
    socket.send(JSON.stringify(msg));
  }

  // ---------------------------------------------------------------- main loop

  function animate() {
    requestAnimationFrame(animate);
    if (latestFrame) {
      applyFrame(latestFrame);
      latestFrame = null;
      frameApplied = true;
      needsRender = true;
    }
    if (fitPending && frameApplied) { fitPending = false; fitCamera(); }
    panel.drawPlot();
    if (needsRender && renderer) {
      needsRender = false;
      renderer.render(scene3, camera);
    }
  }

  panel.init({ sendOp: sendOp });
  connect();
  requestAnimationFrame(animate);
})();
