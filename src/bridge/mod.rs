//! The bridge to Blender and other tools: glTF 2.0 scenes in ([`import`]) and out ([`export`]).
//!
//! Reading a glTF file's geometry is the scene's job (`scene::gltf`, used by every lesson
//! whose `[[object]]` names a `.glb`); this room turns a whole file into a lesson and a lesson
//! into a file, with the units of [`units`].

pub mod export;
pub mod import;
pub mod three_point;
pub mod units;
