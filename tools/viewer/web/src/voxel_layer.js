// Occupied voxels as one instanced mesh of cubes coloured by height. Added and removed voxels
// come as flattened global indices; a removed voxel's slot is filled by the last one.
import * as THREE from "three";
import { heightColor } from "./colors.js";

export class VoxelLayer {
  constructor(parent) {
    this.parent = parent;
    this.resolution = 0.1;
    this.slotOfKey = new Map();
    this.keyOfSlot = [];
    this.material = new THREE.MeshLambertMaterial();
    this.capacity = 0;
    this.mesh = null;
    this.grow(16384);
  }

  get count() {
    return this.keyOfSlot.length;
  }

  grow(capacity) {
    const geometry = new THREE.BoxGeometry(1, 1, 1);
    const mesh = new THREE.InstancedMesh(geometry, this.material, capacity);
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    mesh.frustumCulled = false;
    if (this.mesh) {
      for (let i = 0; i < this.count; i += 1) {
        mesh.setMatrixAt(i, this.matrixOf(this.keyOfSlot[i]));
        mesh.setColorAt(i, heightColor(this.centerOf(this.keyOfSlot[i]).z));
      }
      this.parent.remove(this.mesh);
      this.mesh.dispose();
    } else {
      mesh.setColorAt(0, new THREE.Color());
    }
    mesh.count = this.count;
    this.mesh = mesh;
    this.capacity = capacity;
    this.parent.add(mesh);
  }

  centerOf(key) {
    const [x, y, z] = key.split(",").map(Number);
    const r = this.resolution;
    return new THREE.Vector3((x + 0.5) * r, (y + 0.5) * r, (z + 0.5) * r);
  }

  matrixOf(key) {
    const m = new THREE.Matrix4().makeScale(this.resolution, this.resolution, this.resolution);
    return m.setPosition(this.centerOf(key));
  }

  apply(message) {
    this.resolution = message.resolution;
    if (message.snapshot) {
      this.slotOfKey.clear();
      this.keyOfSlot = [];
    }
    const removed = message.removed;
    for (let i = 0; i + 2 < removed.length; i += 3) this.remove(`${removed[i]},${removed[i + 1]},${removed[i + 2]}`);
    const added = message.added;
    if (this.count + added.length / 3 > this.capacity) {
      let capacity = this.capacity;
      while (capacity < this.count + added.length / 3) capacity *= 2;
      this.grow(capacity);
    }
    for (let i = 0; i + 2 < added.length; i += 3) this.add(`${added[i]},${added[i + 1]},${added[i + 2]}`);
    this.mesh.count = this.count;
    this.mesh.instanceMatrix.needsUpdate = true;
    if (this.mesh.instanceColor) this.mesh.instanceColor.needsUpdate = true;
  }

  add(key) {
    if (this.slotOfKey.has(key)) return;
    const slot = this.keyOfSlot.length;
    this.slotOfKey.set(key, slot);
    this.keyOfSlot.push(key);
    this.mesh.setMatrixAt(slot, this.matrixOf(key));
    this.mesh.setColorAt(slot, heightColor(this.centerOf(key).z));
  }

  remove(key) {
    const slot = this.slotOfKey.get(key);
    if (slot === undefined) return;
    const last = this.keyOfSlot.length - 1;
    const lastKey = this.keyOfSlot[last];
    const m = new THREE.Matrix4();
    const c = new THREE.Color();
    this.mesh.getMatrixAt(last, m);
    this.mesh.getColorAt(last, c);
    this.mesh.setMatrixAt(slot, m);
    this.mesh.setColorAt(slot, c);
    this.keyOfSlot[slot] = lastKey;
    this.slotOfKey.set(lastKey, slot);
    this.keyOfSlot.pop();
    this.slotOfKey.delete(key);
  }
}
