// The 3D view: the scan as points coloured by height, the fitted bore (cylinder, axis, entrance)
// or object parts (superquadric wireframes, thesis eq. 2.10 with the taper of eq. 2.22-2.23) at
// their poses, in the world frame (mm, z up). three.js and its orbit controls come from rangefitd.
import * as THREE from 'three';
import { OrbitControls } from '/OrbitControls.js';

const BACKGROUND = 0x181a1f;

function heightColours(positions) {
  const n = positions.length / 3;
  const zs = [];
  for (let i = 0; i < n; i += Math.max(1, Math.floor(n / 2000))) zs.push(positions[3 * i + 2]);
  zs.sort((a, b) => a - b);
  const lo = zs[Math.floor(0.02 * (zs.length - 1))] ?? 0;
  const hi = zs[Math.floor(0.98 * (zs.length - 1))] ?? 1;
  const colours = new Float32Array(positions.length);
  const c = new THREE.Color();
  for (let i = 0; i < n; ++i) {
    const t = Math.min(1, Math.max(0, (positions[3 * i + 2] - lo) / Math.max(1e-9, hi - lo)));
    c.setHSL(0.66 - 0.66 * t, 0.85, 0.55);  // blue low .. red high
    colours[3 * i] = c.r; colours[3 * i + 1] = c.g; colours[3 * i + 2] = c.b;
  }
  return colours;
}

// Signed power of the superquadric surface.
const spow = (v, e) => Math.sign(v) * Math.pow(Math.abs(v), e);

function superquadricLines(s, rows = 12, cols = 24) {
  const point = (eta, omega) => {
    const z = s.a3 * spow(Math.sin(eta), s.eps1);
    const taperX = (s.kx * z) / s.a3 + 1, taperY = (s.ky * z) / s.a3 + 1;
    return new THREE.Vector3(
      taperX * s.a1 * spow(Math.cos(eta), s.eps1) * spow(Math.cos(omega), s.eps2),
      taperY * s.a2 * spow(Math.cos(eta), s.eps1) * spow(Math.sin(omega), s.eps2), z);
  };
  const pts = [];
  for (let i = 1; i < rows; ++i) {  // parallels
    const eta = -Math.PI / 2 + (Math.PI * i) / rows;
    for (let j = 0; j < cols; ++j) {
      pts.push(point(eta, (2 * Math.PI * j) / cols), point(eta, (2 * Math.PI * (j + 1)) / cols));
    }
  }
  for (let j = 0; j < cols; j += 2) {  // meridians
    const omega = (2 * Math.PI * j) / cols;
    for (let i = 0; i < 2 * rows; ++i) {
      pts.push(point(-Math.PI / 2 + (Math.PI * i) / (2 * rows), omega),
               point(-Math.PI / 2 + (Math.PI * (i + 1)) / (2 * rows), omega));
    }
  }
  return new THREE.BufferGeometry().setFromPoints(pts);
}

function poseOf(part) {
  const [w, x, y, z] = part.quaternion_wxyz;
  const m = new THREE.Matrix4().compose(new THREE.Vector3(...part.translation_mm),
                                        new THREE.Quaternion(x, y, z, w), new THREE.Vector3(1, 1, 1));
  return m;
}

export class View3d {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(BACKGROUND);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.1, 1e6);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.draw());
    this.content = new THREE.Group();
    this.scene.add(this.content);
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  draw() { this.renderer.render(this.scene, this.camera); }

  // cloud: {positions} from parsePly; result: the result JSON (parts, shapes, bore_radius_mm).
  show(cloud, result) {
    this.content.clear();
    const finite = [];
    const p = cloud.positions;
    for (let i = 0; i < p.length; i += 3) {
      if (Number.isFinite(p[i]) && Number.isFinite(p[i + 1]) && Number.isFinite(p[i + 2])) {
        finite.push(p[i], p[i + 1], p[i + 2]);
      }
    }
    const positions = new Float32Array(finite);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(heightColours(positions), 3));
    geometry.computeBoundingSphere();
    const sphere = geometry.boundingSphere;
    const size = Math.max(1, sphere.radius);
    this.content.add(new THREE.Points(geometry, new THREE.PointsMaterial(
      { size: size / 250, vertexColors: true, sizeAttenuation: true })));
    this.addModels(result || {}, size);
    // Look at the model when there is one (a bore is small in its scan), else at the scan.
    let target = sphere.center.clone(), distance = 2.6 * size;
    const part = (result && result.parts || [])[0];
    if (part) {
      target = new THREE.Vector3(...part.translation_mm);
      const shape = result.shapes && result.shapes[part.name];
      const extent = shape ? Math.max(shape.a1, shape.a2, shape.a3) : 4 * (result.bore_radius_mm || 5);
      distance = Math.min(distance, 6 * extent);
    }
    this.controls.target.copy(target);
    this.camera.position.copy(target).add(new THREE.Vector3(0.45, -0.75, 0.55).multiplyScalar(distance));
    this.camera.near = distance / 1000;
    this.camera.far = distance * 20 + 4 * size;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.draw();
    this.container.dataset.points = String(positions.length / 3);
  }

  addModels(result, size) {
    const white = new THREE.LineBasicMaterial({ color: 0xffffff });
    for (const part of result.parts || []) {
      const pose = poseOf(part);
      if (result.kind === 'bore') {
        const r = result.bore_radius_mm, depth = 3 * r;
        // Axis out of the bore toward the sensor (local z): the wall runs from the entrance inward.
        const cyl = new THREE.CylinderGeometry(r, r, depth, 32, 3, true);
        cyl.rotateX(Math.PI / 2).translate(0, 0, -depth / 2);
        const wire = new THREE.LineSegments(new THREE.WireframeGeometry(cyl), white);
        wire.applyMatrix4(pose);
        this.content.add(wire);
        const axis = new THREE.BufferGeometry().setFromPoints(
          [new THREE.Vector3(0, 0, -depth), new THREE.Vector3(0, 0, 2 * r)]);
        const line = new THREE.Line(axis, new THREE.LineBasicMaterial({ color: 0xffd600 }));
        line.applyMatrix4(pose);
        this.content.add(line);
      } else if (result.shapes && result.shapes[part.name]) {
        const wire = new THREE.LineSegments(superquadricLines(result.shapes[part.name]), white);
        wire.applyMatrix4(pose);
        this.content.add(wire);
        const axes = new THREE.AxesHelper(0.15 * size);
        axes.applyMatrix4(pose);
        this.content.add(axes);
      }
    }
  }
}
