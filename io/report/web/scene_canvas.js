// The 3-D view of a comic-sfm report page drawn on a 2-D canvas, for browsers without WebGL (or
// pages written without three.js): scene.js hands the section over when it cannot draw it. The
// points, the camera frusta and paths are projected in perspective from a viewpoint the mouse
// turns about the model (drag) and brings nearer (wheel); no depth test, points over lines in the
// order given. After the first frame it leaves in <html> data-scene="drawn-2d", the points it
// drew inside the canvas (data-scene-points), its drawn pixels (data-scene-pixels) and where the
// canvas is (data-scene-rect), for the headless-browser tests.
(function () {
  'use strict';

  var page = window.ComicPage;
  var el = page.el;
  var BACKGROUND = [0x15, 0x19, 0x1d];

  function bytesOf(base64) {
    var binary = atob(base64);
    var bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }

  function floatsOf(base64) {
    var bytes = bytesOf(base64);
    return new Float32Array(bytes.buffer, 0, bytes.length / 4);
  }

  // Shared with scene.js, which decodes the same section for three.js.
  page.sceneBytes = bytesOf;
  page.sceneFloats = floatsOf;

  function add(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function scale(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  }
  function unit(a) {
    var n = Math.sqrt(dot(a, a));
    return n > 0 ? scale(a, 1 / n) : [0, 0, 0];
  }
  // `v` turned by the unit quaternion (x, y, z, w) at q[k..k+3].
  function rotate(q, k, v) {
    var u = [q[k], q[k + 1], q[k + 2]], w = q[k + 3];
    var t = scale(cross(u, v), 2);
    return add(add(v, scale(t, w)), cross(u, t));
  }

  function quantile(values, fraction) {
    if (!values.length) return 0;
    values.sort(function (a, b) { return a - b; });
    return values[Math.min(values.length - 1, Math.floor(fraction * (values.length - 1)))];
  }

  // The 2nd to 98th percentile box of every position given (so a few far points do not shrink
  // the model to a dot): its centre and diagonal.
  function robustBox(arrays) {
    var low = [], high = [];
    for (var axis = 0; axis < 3; ++axis) {
      var values = [];
      arrays.forEach(function (a) {
        var step = Math.max(1, Math.floor(a.length / 3 / 20000));
        for (var i = axis; i < a.length; i += 3 * step) if (isFinite(a[i])) values.push(a[i]);
      });
      low.push(quantile(values, 0.02));
      high.push(quantile(values.slice(), 0.98));
    }
    var diagonal = Math.sqrt(dot(sub(high, low), sub(high, low)));
    return {center: scale(add(low, high), 0.5), size: Math.max(diagonal, 1e-6)};
  }

  // The cameras' mean viewing direction across `up` (any direction across it without cameras).
  function meanForward(sets, up) {
    var forward = [0, 0, 0];
    sets.forEach(function (set) {
      for (var i = 0; i < set.rotations.length / 4; ++i) {
        forward = add(forward, rotate(set.rotations, 4 * i, [0, 0, 1]));
      }
    });
    forward = sub(forward, scale(up, dot(forward, up)));
    if (dot(forward, forward) < 1e-12) {
      forward = Math.abs(up[0]) > 0.9 ? [0, 0, 1] : [1, 0, 0];
      forward = sub(forward, scale(up, dot(forward, up)));
    }
    return unit(forward);
  }

  function centroid(sets, fallback) {
    var sum = [0, 0, 0], n = 0;
    sets.forEach(function (set) {
      for (var i = 0; i < set.count; ++i) {
        sum = add(sum, [set.centers[3 * i], set.centers[3 * i + 1], set.centers[3 * i + 2]]);
        ++n;
      }
    });
    return n ? scale(sum, 1 / n) : fallback;
  }

  // A perspective camera looking at `view.target` from `view.distance` away, turned by
  // view.yaw about `up` and raised by view.pitch: world point -> [x, y] pixels, or null behind.
  function projector(view, width, height) {
    var across = cross(view.forward, view.up);
    var direction = add(scale(add(scale(view.forward, -Math.cos(view.yaw)),
                                  scale(across, -Math.sin(view.yaw))), Math.cos(view.pitch)),
                        scale(view.up, Math.sin(view.pitch)));
    var eye = add(view.target, scale(direction, view.distance));
    var back = unit(direction);
    var right = unit(cross(view.up, back));
    var upward = cross(back, right);
    var focal = 0.5 * height / Math.tan(25 * Math.PI / 180);
    var near = view.distance * 1e-4;
    return function (x, y, z) {
      var v = [x - eye[0], y - eye[1], z - eye[2]];
      var depth = -dot(v, back);
      if (!(depth > near)) return null;
      return [width / 2 + focal * dot(v, right) / depth, height / 2 - focal * dot(v, upward) / depth];
    };
  }

  // The points as 2x2 pixels straight into the image (fast for hundreds of thousands); returns how
  // many fell inside the canvas.
  function drawPoints(g, points, project, width, height) {
    var image = g.createImageData(width, height);
    var data = image.data;
    for (var p = 0; p < data.length; p += 4) {
      data[p] = BACKGROUND[0];
      data[p + 1] = BACKGROUND[1];
      data[p + 2] = BACKGROUND[2];
      data[p + 3] = 255;
    }
    var drawn = 0;
    for (var i = 0; i < points.count; ++i) {
      var s = project(points.positions[3 * i], points.positions[3 * i + 1],
                      points.positions[3 * i + 2]);
      if (!s) continue;
      var x = Math.floor(s[0]), y = Math.floor(s[1]);
      if (x < 0 || y < 0 || x >= width - 1 || y >= height - 1) continue;
      ++drawn;
      for (var k = 0; k < 4; ++k) {
        var at = 4 * ((y + (k >> 1)) * width + x + (k & 1));
        data[at] = points.colors[3 * i];
        data[at + 1] = points.colors[3 * i + 1];
        data[at + 2] = points.colors[3 * i + 2];
      }
    }
    g.putImageData(image, 0, 0);
    return drawn;
  }

  function segment(g, a, b) {
    if (!a || !b) return;
    g.moveTo(a[0], a[1]);
    g.lineTo(b[0], b[1]);
  }

  // Each camera's path and frusta (apex at the centre, image rectangle `size` ahead).
  function drawCameras(g, set, project, size) {
    g.strokeStyle = set.color;
    g.lineWidth = 1;
    g.beginPath();
    var halfW = 0.5 / set.focal_over_width, halfH = halfW / set.aspect;
    var corners = [[-halfW, -halfH], [halfW, -halfH], [halfW, halfH], [-halfW, halfH]];
    var previous = null;
    for (var i = 0; i < set.count; ++i) {
      var c = [set.centers[3 * i], set.centers[3 * i + 1], set.centers[3 * i + 2]];
      var at = project(c[0], c[1], c[2]);
      segment(g, previous, at);
      previous = at;
      if (!set.rotations.length) continue;
      var s = size * (set.emphasised.length && set.emphasised[i] ? 1.8 : 1);
      var ends = corners.map(function (k) {
        var w = add(rotate(set.rotations, 4 * i, [k[0] * s, k[1] * s, s]), c);
        return project(w[0], w[1], w[2]);
      });
      for (var k = 0; k < 4; ++k) {
        segment(g, at, ends[k]);
        segment(g, ends[k], ends[(k + 1) % 4]);
      }
    }
    g.stroke();
  }

  function drawPath(g, path, project) {
    g.strokeStyle = path.color;
    g.fillStyle = path.color;
    g.lineWidth = 1.5;
    g.beginPath();
    var previous = null;
    for (var i = 0; i < path.count; ++i) {
      var x = path.points[3 * i], y = path.points[3 * i + 1], z = path.points[3 * i + 2];
      var at = isFinite(x) && isFinite(y) && isFinite(z) ? project(x, y, z) : null;
      segment(g, previous, at);
      previous = at;
      if (at && path.dots) g.fillRect(at[0] - 2, at[1] - 2, 4, 4);
    }
    g.stroke();
  }

  function drawnPixels(g, width, height) {
    var data = g.getImageData(0, 0, width, height).data;
    var count = 0;
    for (var i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - BACKGROUND[0]) + Math.abs(data[i + 1] - BACKGROUND[1]) +
          Math.abs(data[i + 2] - BACKGROUND[2]) > 24) {
        ++count;
      }
    }
    return count;
  }

  function decode(section) {
    return {
      points: {count: section.points.count, positions: floatsOf(section.points.positions),
               colors: bytesOf(section.points.colors)},
      sets: section.cameras.map(function (c) {
        return {color: c.color, count: c.count, centers: floatsOf(c.centers),
                rotations: floatsOf(c.rotations), emphasised: c.emphasised, aspect: c.aspect,
                focal_over_width: c.focal_over_width};
      }),
      paths: section.paths.map(function (p) {
        return {color: p.color, count: p.count, points: floatsOf(p.points), dots: p.dots};
      })
    };
  }

  // The view the page opens with: from behind and above the cameras, the way they look on average
  // (as the WebGL view starts).
  function homeView(scene, section) {
    var box = robustBox([scene.points.positions].concat(scene.sets.map(function (s) {
      return s.centers;
    })).concat(scene.paths.map(function (p) { return p.points; })));
    var up = unit([section.up[0], section.up[1], section.up[2]]);
    return {target: scale(add(centroid(scene.sets, box.center), box.center), 0.5), up: up,
            forward: meanForward(scene.sets, up), yaw: 0, pitch: 0.51, distance: 0.92 * box.size,
            size: box.size};
  }

  function leaveCounts(canvas, points, pixels) {
    var root = document.documentElement;
    root.setAttribute('data-scene', 'drawn-2d');
    root.setAttribute('data-scene-points', String(points));
    root.setAttribute('data-scene-pixels', String(pixels));
    var rect = canvas.getBoundingClientRect();
    root.setAttribute('data-scene-rect', [
      Math.round(rect.left + window.pageXOffset), Math.round(rect.top + window.pageYOffset),
      Math.round(rect.width), Math.round(rect.height)].join(','));
  }

  // Turning by drag, nearer and farther by wheel; each change drawn at the next animation frame.
  function listen(canvas, view, redraw) {
    var dragging = null;
    canvas.addEventListener('mousedown', function (event) {
      dragging = [event.clientX, event.clientY];
      event.preventDefault();
    });
    window.addEventListener('mouseup', function () { dragging = null; });
    window.addEventListener('mousemove', function (event) {
      if (!dragging) return;
      view.yaw -= (event.clientX - dragging[0]) * 0.01;
      view.pitch = Math.max(-1.55, Math.min(1.55, view.pitch + (event.clientY - dragging[1]) * 0.01));
      dragging = [event.clientX, event.clientY];
      redraw();
    });
    canvas.addEventListener('wheel', function (event) {
      view.distance *= Math.pow(1.1, event.deltaY > 0 ? 1 : -1);
      event.preventDefault();
      redraw();
    }, {passive: false});
  }

  // Draws `section` (io/report/page_scene.h) into `body`; `reason` says why WebGL is not used.
  page.drawSceneOnCanvas = function (section, body, reason) {
    var width = Math.max(320, Math.min(1160, body.clientWidth || 960)), height = 560;
    var canvas = el('canvas', {width: width, height: height, class: 'scene-2d'});
    var g = canvas.getContext('2d');
    var scene = decode(section);
    var view = homeView(scene, section);
    var home = JSON.parse(JSON.stringify(view));
    var frustum = 0.012 * view.size;
    var draw = function () {
      var project = projector(view, width, height);
      var drawn = drawPoints(g, scene.points, project, width, height);
      scene.sets.forEach(function (set) { drawCameras(g, set, project, frustum); });
      scene.paths.forEach(function (path) { drawPath(g, path, project); });
      return drawn;
    };
    var pending = false;
    var redraw = function () {
      if (pending) return;
      pending = true;
      window.requestAnimationFrame(function () { pending = false; draw(); });
    };
    listen(canvas, view, redraw);
    var reset = el('button', {type: 'button'}, ['reset view']);
    reset.addEventListener('click', function () {
      Object.keys(home).forEach(function (key) { view[key] = JSON.parse(JSON.stringify(home[key])); });
      redraw();
    });
    body.appendChild(el('p', {class: 'notice tone-warning'}, [
      'Drawn without WebGL (' + reason + '): a plain projection of the points and cameras, ' +
      'without depth.']));
    body.appendChild(el('div', {class: 'scene'}, [canvas]));
    body.appendChild(el('div', {class: 'scene-controls'}, [
      el('span', {}, ['drag: turn · wheel: nearer / farther']), reset]));
    var drawn = draw();
    leaveCounts(canvas, drawn, drawnPixels(g, width, height));
  };
})();
