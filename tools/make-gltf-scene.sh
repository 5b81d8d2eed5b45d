#!/bin/sh
# Makes lessons/gltf/three-point.glb (CC0, about 200 kB) from tools/gltf/three-point.toml with
# shadelab's own exporter: the bundled "Blender scene" of lesson 38 and `shadelab import`'s
# examples. Run from anywhere; it builds shadelab first.
set -eu
cd "$(dirname "$0")/.."
cargo build --release --quiet
./target/release/shadelab export tools/gltf/three-point.toml -o lessons/gltf/three-point.glb
