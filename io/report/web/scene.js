// The 3-D view of a comic-sfm report page (io/report/page_scene.h): coloured points, camera
// frusta joined by their path, and other paths (the ground truth), drawn with three.js from
// Debian's libjs-three (inlined into the page before this script) with OrbitControls: drag to
// orbit, right-drag or shift-drag to pan, wheel to zoom. The first frame is drawn at once; later
// frames only when the view moves. Without WebGL or three.js, scene_canvas.js draws the section
// on a 2-D canvas instead. After the first frame the number of drawn (non-background)
// pixels is read back and left in <html data-scene-pixels>, and where the canvas is in
// data-scene-rect (x,y,width,height in CSS pixels), for the headless-browser tests.
(function () {
  'use strict';

  var page = window.ComicPage;
  var el = page.el;
  var BACKGROUND = 0x15191d;

  var bytesOf = page.sceneBytes;  // scene_canvas.js, inlined before this script
  var floatsOf = page.sceneFloats;

  // The value below which `fraction` of `values` lie.
  function quantile(values, fraction) {
    if (!values.length) return 0;
    var sorted = Array.prototype.slice.call(values).sort(function (a, b) { return a - b; });
    return sorted[Math.min(sorted.length - 1, Math.floor(fraction * (sorted.length - 1)))];
  }

  // The region the view frames: 2nd to 98th percentile of the cameras and points on each axis,
  // so a few far points do not shrink the model to a dot.
  function robustBounds(arrays) {
    var low = new THREE.Vector3(), high = new THREE.Vector3();
    for (var axis = 0; axis < 3; ++axis) {
      var values = [];
      arrays.forEach(function (a) {
        var step = Math.max(1, Math.floor(a.length / 3 / 20000));
        for (var i = axis; i < a.length; i += 3 * step) if (isFinite(a[i])) values.push(a[i]);
      });
      low.setComponent(axis, quantile(values, 0.02));
      high.setComponent(axis, quantile(values, 0.98));
    }
    return {low: low, high: high, center: low.clone().add(high).multiplyScalar(0.5),
            size: Math.max(high.clone().sub(low).length(), 1e-6)};
  }

  function lineMaterial(color) {
    return new THREE.LineBasicMaterial({color: new THREE.Color(color)});
  }

  // Few points drawn larger, so a small model is not lost in the dark.
  function pointSize(count) {
    return count < 20000 ? 3 : 2;
  }

  function pointsObject(section) {
    var positions = floatsOf(section.points.positions);
    var colors = bytesOf(section.points.colors);
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3, true));
    var material = new THREE.PointsMaterial({
      size: pointSize(section.points.count), sizeAttenuation: false,
      vertexColors: THREE.VertexColors !== undefined ? THREE.VertexColors : true});
    return {object: new THREE.Points(geometry, material), positions: positions};
  }

  // The median distance between consecutive cameras: the frusta are drawn a fraction of it.
  function typicalSpacing(sets, fallback) {
    var gaps = [];
    sets.forEach(function (c) {
      for (var i = 1; i < c.count; ++i) {
        var dx = c.centers[3 * i] - c.centers[3 * i - 3], dy = c.centers[3 * i + 1] - c.centers[3 * i - 2],
            dz = c.centers[3 * i + 2] - c.centers[3 * i - 1];
        gaps.push(Math.sqrt(dx * dx + dy * dy + dz * dz));
      }
    });
    var median = quantile(gaps, 0.5);
    return median > 0 ? median : fallback;
  }

  // Frusta (apex at the centre, image rectangle at depth `size`) and the path of one camera set.
  function cameraObjects(set, size) {
    var group = new THREE.Group();
    var path = [];
    for (var i = 0; i < set.count; ++i) {
      path.push(new THREE.Vector3(set.centers[3 * i], set.centers[3 * i + 1], set.centers[3 * i + 2]));
    }
    if (path.length >= 2) {
      group.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(path), lineMaterial(set.color)));
    }
    if (!set.rotations.length) return group;
    var halfW = 0.5 / set.focal_over_width, halfH = halfW / set.aspect;
    var corners = [[-halfW, -halfH], [halfW, -halfH], [halfW, halfH], [-halfW, halfH]];
    var vertices = [];
    var q = new THREE.Quaternion();
    for (i = 0; i < set.count; ++i) {
      q.set(set.rotations[4 * i], set.rotations[4 * i + 1], set.rotations[4 * i + 2],
            set.rotations[4 * i + 3]);
      var s = size * (set.emphasised.length && set.emphasised[i] ? 1.8 : 1);
      var world = corners.map(function (c) {
        return new THREE.Vector3(c[0] * s, c[1] * s, s).applyQuaternion(q).add(path[i]);
      });
      for (var k = 0; k < 4; ++k) {
        vertices.push(path[i], world[k], world[k], world[(k + 1) % 4]);
      }
    }
    group.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(vertices),
                                     lineMaterial(set.color)));
    return group;
  }

  // A path broken at NaN points, with dots when asked.
  function pathObjects(path) {
    var group = new THREE.Group();
    var segments = [], dots = [];
    var previous = null;
    for (var i = 0; i < path.count; ++i) {
      var p = new THREE.Vector3(path.points[3 * i], path.points[3 * i + 1], path.points[3 * i + 2]);
      var valid = isFinite(p.x) && isFinite(p.y) && isFinite(p.z);
      if (valid && previous) segments.push(previous, p);
      if (valid) dots.push(p);
      previous = valid ? p : null;
    }
    if (segments.length) {
      group.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(segments),
                                       lineMaterial(path.color)));
    }
    if (path.dots && dots.length) {
      group.add(new THREE.Points(new THREE.BufferGeometry().setFromPoints(dots),
                                 new THREE.PointsMaterial({color: new THREE.Color(path.color),
                                                           size: 5, sizeAttenuation: false})));
    }
    return group;
  }

  // The mean of the camera centres (or of `fallback` without cameras).
  function cameraCentroid(sets, fallback) {
    var sum = new THREE.Vector3(), n = 0;
    sets.forEach(function (set) {
      for (var i = 0; i < set.count; ++i) {
        sum.add(new THREE.Vector3(set.centers[3 * i], set.centers[3 * i + 1], set.centers[3 * i + 2]));
        ++n;
      }
    });
    return n ? sum.multiplyScalar(1 / n) : fallback.clone();
  }

  // Where the view starts: looking at the middle between the cameras and the cloud, from behind
  // and above the cameras, the way they look on average.
  function initialView(sets, bounds, up) {
    var forward = new THREE.Vector3();
    var q = new THREE.Quaternion();
    sets.forEach(function (set) {
      for (var i = 0; i < set.rotations.length / 4; ++i) {
        q.set(set.rotations[4 * i], set.rotations[4 * i + 1], set.rotations[4 * i + 2],
              set.rotations[4 * i + 3]);
        forward.add(new THREE.Vector3(0, 0, 1).applyQuaternion(q));
      }
    });
    forward.sub(up.clone().multiplyScalar(forward.dot(up)));
    if (forward.lengthSq() < 1e-12) {
      forward = new THREE.Vector3(1, 0, 0);
      if (Math.abs(forward.dot(up)) > 0.9) forward.set(0, 0, 1);
      forward.sub(up.clone().multiplyScalar(forward.dot(up)));
    }
    forward.normalize();
    var target = cameraCentroid(sets, bounds.center).add(bounds.center).multiplyScalar(0.5);
    var position = target.clone()
        .add(forward.multiplyScalar(-0.8 * bounds.size))
        .add(up.clone().multiplyScalar(0.45 * bounds.size));
    return {target: target, position: position};
  }

  // Background-coloured pixels differ from drawn ones; count the drawn.
  function drawnPixels(renderer) {
    var gl = renderer.getContext();
    var w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    var pixels = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    var r = (BACKGROUND >> 16) & 255, g = (BACKGROUND >> 8) & 255, b = BACKGROUND & 255;
    var count = 0;
    for (var i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - r) + Math.abs(pixels[i + 1] - g) + Math.abs(pixels[i + 2] - b) > 24) {
        ++count;
      }
    }
    return count;
  }

  function legendEntries(section) {
    var entries = [];
    section.cameras.forEach(function (c) {
      entries.push({color: c.color, label: c.name + ': ' + c.count + ' cameras (frusta and path)'});
    });
    section.paths.forEach(function (p) { entries.push({color: p.color, label: p.name}); });
    return entries;
  }

  page.renderers.scene = function (section, body, data) {
    var total = section.points.total, shown = section.points.count;
    var pointWords = shown === total ? total + ' points' :
        'showing ' + shown + ' of ' + total + ' points (every ' + section.points.stride +
        'th: the model is subsampled for the view)';
    // Without three.js or WebGL the same section is drawn on a 2-D canvas (scene_canvas.js).
    var withoutWebGL = function (reason) {
      body.appendChild(page.legend(legendEntries(section)));
      page.drawSceneOnCanvas(section, body, reason);
      body.appendChild(page.note(pointWords + '. Units: ' + (section.unit || 'model units') +
                                 '. ' + (section.note || '')));
    };
    if (typeof THREE === 'undefined' || !THREE.OrbitControls) {
      withoutWebGL(data && data.three_js_missing ? data.three_js_missing : 'three.js did not load');
      return;
    }
    var width = Math.max(320, Math.min(1160, body.clientWidth || 960)), height = 560;
    var renderer;
    try {
      renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    } catch (error) {
      withoutWebGL('this browser offers no WebGL: ' + error.message);
      return;
    }
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(width, height);
    renderer.setClearColor(BACKGROUND, 1);
    var scene = new THREE.Scene();
    var points = pointsObject(section);
    scene.add(points.object);
    var sets = section.cameras.map(function (c) {
      return {name: c.name, color: c.color, count: c.count, centers: floatsOf(c.centers),
              rotations: floatsOf(c.rotations), emphasised: c.emphasised, aspect: c.aspect,
              focal_over_width: c.focal_over_width};
    });
    var paths = section.paths.map(function (p) {
      return {color: p.color, count: p.count, points: floatsOf(p.points), dots: p.dots};
    });
    var bounds = robustBounds([points.positions].concat(sets.map(function (s) { return s.centers; }))
                                  .concat(paths.map(function (p) { return p.points; })));
    var frustum = Math.min(Math.max(0.6 * typicalSpacing(sets, 0.02 * bounds.size),
                                    0.004 * bounds.size), 0.04 * bounds.size);
    sets.forEach(function (set) { scene.add(cameraObjects(set, frustum)); });
    paths.forEach(function (path) { scene.add(pathObjects(path)); });

    var up = new THREE.Vector3(section.up[0], section.up[1], section.up[2]).normalize();
    var camera = new THREE.PerspectiveCamera(50, width / height, bounds.size * 1e-4, bounds.size * 100);
    camera.up.copy(up);
    var home = initialView(sets, bounds, up);
    camera.position.copy(home.position);
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(home.target);
    controls.screenSpacePanning = true;
    controls.update();
    var draw = function () { renderer.render(scene, camera); };
    controls.addEventListener('change', draw);

    var view = el('div', {class: 'scene'}, [renderer.domElement]);
    var size = el('input', {type: 'range', min: '1', max: '8', step: '0.5',
                            value: String(pointSize(section.points.count))});
    size.addEventListener('input', function () {
      points.object.material.size = Number(size.value);
      draw();
    });
    var reset = el('button', {type: 'button'}, ['reset view']);
    reset.addEventListener('click', function () {
      camera.position.copy(home.position);
      controls.target.copy(home.target);
      controls.update();
      draw();
    });
    body.appendChild(page.legend(legendEntries(section)));
    body.appendChild(view);
    body.appendChild(el('div', {class: 'scene-controls'}, [
      el('span', {}, ['drag: orbit · right-drag or shift-drag: pan · wheel: zoom']),
      el('label', {}, ['point size ', size]), reset]));
    body.appendChild(page.note(pointWords + '. Units: ' + (section.unit || 'model units') +
                               '. ' + (section.note || '')));
    draw();
    var drawn = drawnPixels(renderer);
    renderer.domElement.setAttribute('data-drawn-pixels', String(drawn));
    document.documentElement.setAttribute('data-scene', 'drawn');
    document.documentElement.setAttribute('data-scene-pixels', String(drawn));
    var rect = renderer.domElement.getBoundingClientRect();
    document.documentElement.setAttribute('data-scene-rect', [
      Math.round(rect.left + window.pageXOffset), Math.round(rect.top + window.pageYOffset),
      Math.round(rect.width), Math.round(rect.height)].join(','));
    window.addEventListener('resize', function () {
      var w = Math.max(320, Math.min(1160, body.clientWidth || width));
      renderer.setSize(w, height);
      camera.aspect = w / height;
      camera.updateProjectionMatrix();
      draw();
    });
  };
})();
