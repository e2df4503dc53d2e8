// Spheres of large worlds drawn as impostors: one point sprite per sphere,
// shaded as a sphere in the fragment shader, all spheres in one draw of one
// vertex each. The software renderer of a machine without a GPU (SwiftShader)
// spends about 1 us per triangle and ~18 us per instance of an instanced draw,
// so 2000 instanced spheres cannot be drawn at 60 Hz there; 2000 points can.
// The depth is that of the sphere's centre: silhouettes and shading are exact,
// the order is approximate only where two spheres overlap.
import * as THREE from "three";

const vertexShader = /* glsl */ `
  attribute float radius;
  attribute vec3 color;
  uniform float viewportHeight;
  varying vec3 vColor;
  void main() {
    vec4 centre = modelViewMatrix * vec4(position, 1.0);
    gl_Position = projectionMatrix * centre;
    // Diameter on screen (px) of a sphere of this radius at this depth.
    gl_PointSize = radius > 0.0 ? radius * projectionMatrix[1][1] * viewportHeight / -centre.z : 0.0;
    vColor = color;
  }`;

const fragmentShader = /* glsl */ `
  varying vec3 vColor;
  void main() {
    vec2 c = vec2(gl_PointCoord.x * 2.0 - 1.0, 1.0 - gl_PointCoord.y * 2.0);
    float r2 = dot(c, c);
    if (r2 > 1.0) discard;
    vec3 normal = vec3(c, sqrt(1.0 - r2)); // view space
    float light = 0.45 + 0.55 * max(dot(normal, normalize(vec3(0.3, 0.5, 0.8))), 0.0);
    gl_FragColor = vec4(vColor * light, 1.0);
  }`;

const position = new THREE.Vector3();
const scale = new THREE.Vector3();
const rotation = new THREE.Quaternion();
const sphere = new THREE.Sphere();
const hitPoint = new THREE.Vector3();

// The parts of InstancedMesh's interface the scene uses: setMatrixAt (the
// matrix's translation is the centre, its scale the radius), setColorAt,
// posesChanged, colorsChanged; instance ids in ray hits.
export class SphereImpostors extends THREE.Points {
  constructor(count) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * count), 3).setUsage(THREE.DynamicDrawUsage));
    geometry.setAttribute("radius", new THREE.BufferAttribute(new Float32Array(count), 1).setUsage(THREE.DynamicDrawUsage));
    geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * count), 3));
    const material = new THREE.ShaderMaterial({ vertexShader, fragmentShader, uniforms: { viewportHeight: { value: 600 } } });
    super(geometry, material);
    this.count = count;
    this.frustumCulled = false;
    this.onBeforeRender = (renderer) => {
      material.uniforms.viewportHeight.value = renderer.getDrawingBufferSize(new THREE.Vector2()).y;
    };
  }

  setMatrixAt(i, matrix) {
    matrix.decompose(position, rotation, scale);
    this.geometry.attributes.position.setXYZ(i, position.x, position.y, position.z);
    this.geometry.attributes.radius.setX(i, scale.x);
  }

  setColorAt(i, color) {
    this.geometry.attributes.color.setXYZ(i, color.r, color.g, color.b);
  }

  posesChanged() {
    this.geometry.attributes.position.needsUpdate = true;
    this.geometry.attributes.radius.needsUpdate = true;
  }

  colorsChanged() {
    this.geometry.attributes.color.needsUpdate = true;
  }

  dispose() {
    this.geometry.dispose();
    this.material.dispose();
  }

  // Ray-sphere intersection (a point sprite has no triangles to hit).
  raycast(raycaster, intersects) {
    const positions = this.geometry.attributes.position;
    const radii = this.geometry.attributes.radius;
    for (let i = 0; i < this.count; i++) {
      if (radii.getX(i) <= 0) continue;
      sphere.center.fromBufferAttribute(positions, i).applyMatrix4(this.matrixWorld);
      sphere.radius = radii.getX(i);
      if (raycaster.ray.intersectSphere(sphere, hitPoint)) {
        const distance = raycaster.ray.origin.distanceTo(hitPoint);
        if (distance >= raycaster.near && distance <= raycaster.far) {
          intersects.push({ distance, point: hitPoint.clone(), object: this, instanceId: i });
        }
      }
    }
  }
}
