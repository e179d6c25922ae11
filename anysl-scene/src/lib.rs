//! RIB scenes: what `anysl render scene.rib` needs between the RIB reader and the renderers.
//!
//! [`geom`] cuts every RenderMan geometric primitive (quadrics, polygons, patches, NURBS, the
//! teapot) into triangles that carry the exact surface's shading data (u, v, s, t, dPdu, dPdv,
//! normals and the primitive variables).
//!
//! ```
//! use anysl_scene::geom::{sphere, Detail};
//! use anysl_rib::ParamList;
//!
//! let t = sphere(1.0, -1.0, 1.0, 360.0, &ParamList::new(), &Detail::default()).unwrap();
//! assert!(t.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-5));
//! assert_eq!(t.normals.len(), t.positions.len());
//! ```

#![warn(missing_docs)]

pub mod build;
pub mod depth;
pub mod film;
pub mod geom;
pub mod lights;
pub mod render;
pub mod shaders;
pub mod surface;
