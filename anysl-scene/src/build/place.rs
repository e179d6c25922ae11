//! Placing primitives: a tessellated primitive becomes a mesh and an instance (or a part of the
//! object being recorded), with its surface slot (surface shader, displacement and the
//! primitive variables that bind to shader parameters) and its light list.

use super::{Attributes, Block, ObjectPart, SceneBuilder, ShaderCall, VolumeCalls};
use crate::geom::{self, Tessellation};
use anysl_renderers::{Instance, Mesh};
use anysl_rib::{BuildError, ParamList};
use glam::{Mat4, Vec4};

impl SceneBuilder {
    /// The surface shader index for the current attributes (calls with equal parameters,
    /// displacement and volumes share one).
    pub(super) fn surface_index(
        surfaces: &mut Vec<ShaderCall>,
        displacements: &mut Vec<Option<ShaderCall>>,
        volumes: &mut Vec<VolumeCalls>,
        attrs: &Attributes,
        primvars: &ParamList,
    ) -> usize {
        let mut call = attrs.surface.clone().unwrap_or(ShaderCall {
            name: "defaultsurface".into(),
            params: ParamList::new(),
            primvars: ParamList::new(),
            loc: None,
        });
        call.primvars = primvars.clone();
        let same_displacement = |d: &Option<ShaderCall>| match (d, &attrs.displacement) {
            (None, None) => true,
            (Some(a), Some(b)) => a.same_as(b),
            _ => false,
        };
        if let Some(k) = surfaces
            .iter()
            .zip(displacements.iter())
            .zip(volumes.iter())
            .position(|((s, d), v)| s.same_as(&call) && same_displacement(d) && v.same_as(&attrs.volumes))
        {
            return k;
        }
        surfaces.push(call);
        displacements.push(attrs.displacement.clone());
        volumes.push(attrs.volumes.clone());
        surfaces.len() - 1
    }

    pub(super) fn place(&mut self, mesh: usize, transform: Mat4, attrs: &Attributes, primvars: &ParamList) {
        let surface =
            Self::surface_index(&mut self.surfaces, &mut self.displacements, &mut self.volumes, attrs, primvars);
        let mut inst = Instance::new(mesh, surface, transform);
        inst.color = attrs.color;
        inst.opacity = attrs.opacity;
        inst.two_sided = attrs.two_sided;
        // The normals are carried by the inverse transpose, which keeps them on the same side
        // of the surface under a mirroring transform: exactly what RenderMan's rule (flip the
        // cross product dPdu × dPdv when the orientation and the handedness differ) gives with
        // the default orientation. Only "inside" (after the handedness check of `Orientation
        // "lh"/"rh"`) turns them around.
        inst.flip_normals = attrs.inside;
        let mut list = Vec::new();
        for (k, on) in attrs.lights_on.iter().enumerate() {
            if *on {
                self.light_used[k] = true;
                list.push(k as u32);
            }
        }
        let index = match self.light_list_index.get(&list) {
            Some(&i) => i,
            None => {
                let i = self.light_lists.len() as u32;
                self.light_list_index.insert(list.clone(), i);
                self.light_lists.push(list);
                i
            }
        };
        self.instance_lights.push(index);
        self.instances.push(inst);
        self.shader_spaces.push(attrs.shader_space);
    }

    /// Adds a tessellated primitive under the current transform and attributes.
    pub(super) fn add(
        &mut self,
        result: Result<Tessellation, geom::GeomError>,
        what: &str,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        if self.block != Block::World {
            return Err(BuildError::error(format!("{what} outside WorldBegin/WorldEnd")));
        }
        let mut t = match result {
            Ok(t) => t,
            Err(e) => return Err(BuildError::warning(format!("{what} skipped: {}", e.0))),
        };
        let warnings = std::mem::take(&mut t.warnings);
        if !t.triangles.is_empty() {
            if let Some(st) = self.attrs.st {
                // TextureCoordinates: s,t bilinear in (u, v) between the four corners.
                t.st =
                    t.uv.iter()
                        .map(|uv| {
                            let (u, v) = (uv.x, uv.y);
                            let lerp = |a: f32, b: f32, c: f32, d: f32| {
                                (a * (1.0 - u) + b * u) * (1.0 - v) + (c * (1.0 - u) + d * u) * v
                            };
                            glam::Vec2::new(lerp(st[0], st[2], st[4], st[6]), lerp(st[1], st[3], st[5], st[7]))
                        })
                        .collect();
            }
            let projective = self.ctm.row(3) != Vec4::W;
            let mut mesh = Mesh {
                positions: t.positions,
                normals: t.normals,
                uvs: t.uv,
                triangles: t.triangles,
                st: Some(t.st),
                dpdu_dpdv: Some((t.dpdu, t.dpdv)),
                cs: t.cs,
                os: t.os,
            };
            let transform = if projective && self.recording.is_none() {
                // A projective transform (`Perspective`) is applied to the vertices here.
                let m = self.ctm;
                for p in &mut mesh.positions {
                    *p = m.project_point3(*p);
                }
                mesh.dpdu_dpdv = None;
                Mat4::IDENTITY
            } else {
                self.ctm
            };
            self.meshes.push(mesh);
            let index = self.meshes.len() - 1;
            match &mut self.recording {
                Some((_, base, parts)) => parts.push(ObjectPart {
                    mesh: index,
                    relative: base.inverse() * transform,
                    attrs: self.attrs.clone(),
                    primvars: ShaderCall::binding_primvars(params),
                }),
                None => {
                    let attrs = self.attrs.clone();
                    self.place(index, transform, &attrs, &ShaderCall::binding_primvars(params));
                }
            }
        }
        if warnings.is_empty() {
            Ok(())
        } else {
            Err(BuildError::warning(format!("{what}: {}", warnings.join("; "))))
        }
    }
}
