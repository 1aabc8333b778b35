/*
 * servoloop view — the side panel and HUD status of the page.
 *
 * Controllers per robot (start/stop, E-STOP), world controls (pause, unpause, step,
 * reset), the joint picker with its live plot of the last 10 s of simulated time,
 * the warnings list and the connection status. view.js owns the WebSocket and calls
 * these functions through window.servoloopPanel; buttons send their requests through
 * the sendOp function view.js passes to init().
 */
(function () {
  'use strict';

  function $(id) { return document.getElementById(id); }
  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  var sendOp = function () {};
  var control = false;          // hello.control: show buttons and send requests

  // ------------------------------------------------------------------ warnings

  var MAX_WARNINGS = 100;
  var warnings = new Map();     // text -> {li, count}; a repeated warning only bumps its count

  function addWarning(text) {
    var list = $('warnings');
    var w = warnings.get(text);
    if (w) {
      w.count++;
      w.li.textContent = text + ' (\u00d7' + w.count + ')';
      list.insertBefore(w.li, list.firstChild);   // newest first
      return;
    }
    var li = el('li', null, text);
    li.warningText = text;
    warnings.set(text, { li: li, count: 1 });
    list.insertBefore(li, list.firstChild);
    while (list.children.length > MAX_WARNINGS) {
      var old = list.lastChild;
      warnings.delete(old.warningText);
      list.removeChild(old);
    }
  }

  function setStatus(connected) {
    var s = $('status');
    s.textContent = connected ? 'connected' : 'disconnected \u2014 retrying';
    s.className = connected ? 'connected' : 'disconnected';
  }

  // --------------------------------------------------------------- controllers

  var robotSections = {};       // ns -> {el, safety, estop, list, rows: {name -> row}}

  // The server's hello decides whether the page may control; rebuild the panel with or
  // without buttons.
  function setControl(on) {
    control = on;
    var wc = $('world-controls');
    wc.hidden = !on;
    Array.prototype.forEach.call(wc.querySelectorAll('button'), function (b) { b.disabled = !on; });
    $('controllers').textContent = '';
    robotSections = {};
    if (window.servoloopView.controllers) setControllers(window.servoloopView.controllers);
  }

  function makeRobot(ns) {
    var sec = { el: el('div', 'robot'), rows: {} };
    sec.el.dataset.ns = ns;
    var head = el('div', 'robot-head');
    head.appendChild(el('h3', null, ns));
    sec.safety = el('span', 'safety');
    head.appendChild(sec.safety);
    if (control) {
      sec.estop = el('button', 'estop', 'E-STOP');
      sec.estop.addEventListener('click', function () {
        sendOp({ op: 'estop', ns: ns, engaged: sec.estop.dataset.engaged !== 'true' }, sec.estop);
      });
      head.appendChild(sec.estop);
    }
    sec.el.appendChild(head);
    sec.list = el('div', 'controller-list');
    sec.el.appendChild(sec.list);
    return sec;
  }

  function makeRow(ns, name) {
    var row = { el: el('div', 'controller') };
    row.el.dataset.name = name;
    row.name = el('span', 'name', name);
    row.type = el('span', 'type');
    row.state = el('span', 'state');
    row.el.appendChild(row.name);
    row.el.appendChild(row.state);
    row.el.appendChild(row.type);
    if (control) {
      row.toggle = el('button', 'toggle');
      row.toggle.addEventListener('click', function () {
        var running = row.el.dataset.state === 'running';
        sendOp({ op: 'switch', ns: ns, start: running ? [] : [name], stop: running ? [name] : [] }, row.toggle);
      });
      row.el.appendChild(row.toggle);
    }
    return row;
  }

  // Updates the panel in place (elements are kept so clicks are never lost to a redraw).
  function setControllers(msg) {
    var box = $('controllers');
    var seen = {};
    (msg.robots || []).forEach(function (r) {
      seen[r.ns] = true;
      var sec = robotSections[r.ns];
      if (!sec) { sec = robotSections[r.ns] = makeRobot(r.ns); box.appendChild(sec.el); }
      var safety = r.safety || (r.estop ? 'emergency_stop' : 'running');
      sec.safety.textContent = safety.replace(/_/g, ' ');
      sec.safety.dataset.safety = safety;
      if (sec.estop) {
        sec.estop.dataset.engaged = r.estop ? 'true' : 'false';
        sec.estop.textContent = r.estop ? 'Release' : 'E-STOP';
      }
      var rowSeen = {};
      (r.controllers || []).forEach(function (c) {
        rowSeen[c.name] = true;
        var row = sec.rows[c.name];
        if (!row) { row = sec.rows[c.name] = makeRow(r.ns, c.name); sec.list.appendChild(row.el); }
        row.el.dataset.state = c.state;
        row.type.textContent = c.type || '';
        row.state.textContent = c.state;
        if (row.toggle) row.toggle.textContent = c.state === 'running' ? 'Stop' : 'Start';
      });
      Object.keys(sec.rows).forEach(function (n) {
        if (!rowSeen[n]) { sec.list.removeChild(sec.rows[n].el); delete sec.rows[n]; }
      });
    });
    Object.keys(robotSections).forEach(function (ns) {
      if (!seen[ns]) { box.removeChild(robotSections[ns].el); delete robotSections[ns]; }
    });
  }

  // ------------------------------------------------------ joint picker and plot

  var WINDOW = 10;              // seconds of simulated time shown
  var N = 1100;                 // samples kept; with MIN_DT this always covers WINDOW
  var MIN_DT = WINDOW / 1000;   // thinner samples are skipped (fast sim, slow frames)
  var COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];

  // One ring of sample times shared by all joints; one value ring per joint key "/ns:joint".
  var plot = {
    times: new Float64Array(N), head: 0, count: 0, lastT: -Infinity,
    series: {},               // key -> Float64Array(N), NaN where the joint had no value
    index: {},                // ns -> keys in joint_names order
    checked: [],              // ticked keys, in tick order
    defaulted: false,         // the first scene ticked its models' first joints
    colors: {},               // key -> colour of a ticked key
    dirty: true, lastDraw: 0
  };

  // Rebuilds the picker for a new scene, keeping ticks and history of joints that remain.
  function setScene(msg) {
    var picker = $('joint-picker');
    picker.textContent = '';
    var series = {};
    plot.index = {};
    (msg.models || []).forEach(function (m) {
      var names = m.joint_names || [];
      plot.index[m.ns] = names.map(function (n) { return m.ns + ':' + n; });
      if (!names.length) return;
      var group = el('div', 'model-joints');
      group.appendChild(el('div', 'model-name', m.ns));
      names.forEach(function (n) {
        var key = m.ns + ':' + n;
        series[key] = plot.series[key] || new Float64Array(N).fill(NaN);
        var label = el('label');
        var box = el('input');
        box.type = 'checkbox';
        box.dataset.joint = key;
        box.checked = plot.checked.indexOf(key) >= 0;
        box.addEventListener('change', function () { tick(key, box.checked); });
        var swatch = el('span', 'swatch');
        swatch.dataset.joint = key;
        label.appendChild(box);
        label.appendChild(swatch);
        label.appendChild(document.createTextNode(n));
        group.appendChild(label);
      });
      picker.appendChild(group);
    });
    plot.series = series;
    plot.checked.slice().forEach(function (k) { if (!series[k]) tick(k, false); });
    // Something to see at once: the first joint of each model (up to four),
    // on the first scene only, so that the user's choice is kept after it.
    if (!plot.defaulted) {
      plot.defaulted = true;
      Object.keys(plot.index).map(function (ns) { return plot.index[ns][0]; })
        .filter(function (key) { return key; }).slice(0, 4).forEach(function (key) {
          tick(key, true);
          var box = picker.querySelector('input[data-joint="' + key.replace(/"/g, '\\"') + '"]');
          if (box) box.checked = true;
        });
    }
    paintSwatches();
    plot.dirty = true;
  }

  function tick(key, on) {
    var i = plot.checked.indexOf(key);
    if (on && i < 0) {
      plot.checked.push(key);
      var used = plot.checked.map(function (k) { return plot.colors[k]; });
      plot.colors[key] = COLORS.filter(function (c) { return used.indexOf(c) < 0; })[0] ||
                         COLORS[plot.checked.length % COLORS.length];
    } else if (!on && i >= 0) {
      plot.checked.splice(i, 1);
      delete plot.colors[key];
    }
    paintSwatches();
    plot.dirty = true;
  }

  function paintSwatches() {
    Array.prototype.forEach.call($('joint-picker').querySelectorAll('.swatch'), function (s) {
      s.style.background = plot.colors[s.dataset.joint] || 'transparent';
    });
  }

  // Stores every joint of a frame (so a newly ticked joint already has its history).
  function recordFrame(f) {
    var t = f.t;
    if (typeof t !== 'number') return;
    if (t < plot.lastT - 1e-9) { plot.count = 0; plot.lastT = -Infinity; }  // time went back (reset)
    if (t < plot.lastT + MIN_DT) return;
    var i = plot.head, k;
    plot.times[i] = t;
    for (k in plot.series) plot.series[k][i] = NaN;
    (f.models || []).forEach(function (fm) {
      var keys = plot.index[fm.ns], q = fm.q || [];
      if (!keys) return;
      for (var j = 0; j < keys.length && j < q.length; j++) {
        if (typeof q[j] === 'number') plot.series[keys[j]][i] = q[j];
      }
    });
    plot.head = (i + 1) % N;
    plot.count = Math.min(plot.count + 1, N);
    plot.lastT = t;
    plot.dirty = true;
  }

  // A "nice" tick step (1, 2 or 5 times a power of ten) for a range.
  function niceStep(range, ticks) {
    var raw = range / ticks, p = Math.pow(10, Math.floor(Math.log10(raw))), r = raw / p;
    return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * p;
  }

  // Redraws the plot when new data or ticks arrived, at most ~30 times a second.
  function drawPlot() {
    var now = performance.now();
    if (!plot.dirty || now - plot.lastDraw < 33) return;
    plot.dirty = false;
    plot.lastDraw = now;

    var canvas = $('plot'), dpr = window.devicePixelRatio || 1;
    var W = canvas.clientWidth || 300, H = canvas.clientHeight || 180;
    if (canvas.width !== Math.round(W * dpr) || canvas.height !== Math.round(H * dpr)) {
      canvas.width = Math.round(W * dpr);
      canvas.height = Math.round(H * dpr);
    }
    var g = canvas.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, W, H);
    g.font = '10px sans-serif';
    var L = 42, R = W - 6, T = 6, B = H - 16;     // plot area
    g.fillStyle = '#fff';
    g.fillRect(L, T, R - L, B - T);

    var tEnd = Math.max(plot.count ? plot.lastT : 0, WINDOW), tStart = tEnd - WINDOW;   // 0..10 s at start
    var start = (plot.head - plot.count + N) % N, i, n, v;

    // y range over the visible samples of the ticked joints
    var lo = Infinity, hi = -Infinity;
    plot.checked.forEach(function (key) {
      var s = plot.series[key];
      for (n = 0; n < plot.count; n++) {
        i = (start + n) % N;
        v = s[i];
        if (plot.times[i] >= tStart && v === v) { if (v < lo) lo = v; if (v > hi) hi = v; }
      }
    });
    if (lo > hi) { lo = -1; hi = 1; }
    if (hi - lo < 1e-6) { var c = (hi + lo) / 2, d = Math.max(Math.abs(c) * 0.1, 0.05); lo = c - d; hi = c + d; }
    var pad = (hi - lo) * 0.08;
    lo -= pad; hi += pad;
    var X = function (t) { return L + (t - tStart) / WINDOW * (R - L); };
    var Y = function (y) { return B - (y - lo) / (hi - lo) * (B - T); };

    // grid and labels
    g.strokeStyle = '#e2e2e2';
    g.fillStyle = '#555';
    g.lineWidth = 1;
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    var step = niceStep(hi - lo, 4);
    for (v = Math.ceil(lo / step) * step; v <= hi; v += step) {
      g.beginPath(); g.moveTo(L, Math.round(Y(v)) + 0.5); g.lineTo(R, Math.round(Y(v)) + 0.5); g.stroke();
      // Short labels: large or tiny values in exponent form, so they fit the margin.
      var label = Math.abs(v) < step / 1e6 ? '0'
                : (Math.abs(v) >= 1e4 || Math.abs(v) < 1e-3) ? v.toExponential(1) : +v.toPrecision(3) + '';
      g.fillText(label, L - 4, Y(v));
    }
    g.textAlign = 'center';
    g.textBaseline = 'top';
    for (v = Math.ceil(tStart / 2) * 2; v <= tEnd; v += 2) {
      g.beginPath(); g.moveTo(Math.round(X(v)) + 0.5, T); g.lineTo(Math.round(X(v)) + 0.5, B); g.stroke();
      g.fillText(v.toFixed(0) + ' s', X(v), B + 3);
    }
    g.strokeStyle = '#999';
    g.strokeRect(L + 0.5, T + 0.5, R - L - 1, B - T - 1);

    if (!plot.checked.length) {
      g.fillStyle = '#888';
      g.textBaseline = 'middle';
      g.fillText('tick joints below to plot them', (L + R) / 2, (T + B) / 2);
      return;
    }

    // one line per ticked joint, broken where it had no value
    g.save();
    g.beginPath(); g.rect(L, T, R - L, B - T); g.clip();
    g.lineWidth = 1.5;
    plot.checked.forEach(function (key) {
      var s = plot.series[key], pen = false;
      g.strokeStyle = plot.colors[key];
      g.beginPath();
      for (n = 0; n < plot.count; n++) {
        i = (start + n) % N;
        v = s[i];
        if (plot.times[i] < tStart - 0.1 || v !== v) { pen = false; continue; }
        if (pen) g.lineTo(X(plot.times[i]), Y(v)); else g.moveTo(X(plot.times[i]), Y(v));
        pen = true;
      }
      g.stroke();
    });
    g.restore();

    // legend, top-left inside the plot area
    g.textAlign = 'left';
    g.textBaseline = 'middle';
    plot.checked.forEach(function (key, idx) {
      var y = T + 9 + idx * 12;
      g.fillStyle = 'rgba(255,255,255,0.8)';
      g.fillRect(L + 3, y - 6, g.measureText(key).width + 22, 12);
      g.fillStyle = plot.colors[key];
      g.fillRect(L + 6, y - 1.5, 12, 3);
      g.fillStyle = '#222';
      g.fillText(key, L + 22, y);
    });
  }

  // ------------------------------------------------------------- world controls

  function init(opts) {
    sendOp = opts.sendOp;
    var wc = {
      pause: { op: 'pause' }, unpause: { op: 'unpause' },
      step: { op: 'step', steps: 100 }, reset: { op: 'reset' }
    };
    Object.keys(wc).forEach(function (id) {
      var b = $(id);
      b.addEventListener('click', function () {
        var msg = {};
        for (var f in wc[id]) msg[f] = wc[id][f];
        sendOp(msg, b);
      });
    });
    setControl(false);        // until the server's hello says otherwise
    setStatus(false);
  }

  window.servoloopPanel = {
    init: init, addWarning: addWarning, setStatus: setStatus, setControl: setControl,
    setControllers: setControllers, setScene: setScene, recordFrame: recordFrame, drawPlot: drawPlot
  };
})();
