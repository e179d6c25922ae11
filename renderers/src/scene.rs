//! [`Scene`]: camera, meshes placed by [`Instance`]s, surface shaders, lights and the sky —
//! generic over the surface-shader type `S` and the light type `L`, so renderer code never
//! names a concrete shader. Building a scene flattens every instance into world-space
//! triangles and builds the BVH once.

use crate::accel::{Accel, Hit, RayPacket, MAX_PACKET};
use crate::camera::{Camera, RayDifferential};
use crate::mesh::Mesh;
use anysl_core::Spaces;
use glam::{Mat4, Vec2, Vec3, Vec3A};
use std::fmt;

/// A mesh placed in the world with a surface shader and the attributes RenderMan attaches to
/// a primitive: its colour and opacity, one- or two-sidedness and orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index into the scene's meshes.
    pub mesh: usize,
    /// Index into the scene's surface shaders.
    pub surface: usize,
    /// Object-to-world transform (glam convention: column vectors, `p' = M · p`).
    pub transform: Mat4,
    /// `Cs` where the mesh has no per-vertex colours.
    pub color: [f32; 3],
    /// `Os` where the mesh has no per-vertex opacities.
    pub opacity: [f32; 3],
    /// Seen from both sides (RenderMan `Sides 2`); one-sided instances are invisible to
    /// camera rays that meet their back (the side away from the shading normal).
    pub two_sided: bool,
    /// Turn the normals around (RenderMan orientation rules: `Orientation "inside"`,
    /// `ReverseOrientation`, or a mirroring object-to-camera transform).
    pub flip_normals: bool,
}

impl Instance {
    /// Mesh `mesh` with surface shader `surface` placed by `transform`: white, opaque,
    /// two-sided, normals as given.
    #[must_use]
    pub fn new(mesh: usize, surface: usize, transform: Mat4) -> Self {
        Self { mesh, surface, transform, color: [1.0; 3], opacity: [1.0; 3], two_sided: true, flip_normals: false }
    }
}

/// What rays that leave the scene see: a vertical gradient from `horizon` (direction
/// horizontal) to `zenith` (straight up or down), the same one [`anysl_core::PointContext`]
/// uses. Camera rays that miss see it only when `visible_to_camera` is set (the AnySL
/// workload wants black there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// Colour towards the horizon.
    pub horizon: [f32; 3],
    /// Colour straight up (and down).
    pub zenith: [f32; 3],
    /// Whether camera rays that miss everything show the sky (else black).
    pub visible_to_camera: bool,
}

impl Default for Sky {
    fn default() -> Self {
        Self { horizon: [0.6, 0.6, 0.6], zenith: [0.2, 0.3, 0.8], visible_to_camera: false }
    }
}

impl Sky {
    /// The sky colour in direction `dir` (any length).
    #[inline]
    #[must_use]
    pub fn color(&self, dir: Vec3A) -> [f32; 3] {
        let d = dir.normalize_or_zero();
        let t = d.y.abs().min(1.0);
        [0, 1, 2].map(|c| self.horizon[c] + (self.zenith[c] - self.horizon[c]) * t)
    }
}

/// Why a scene could not be built.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError(pub String);

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}

/// One triangle of the flattened scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleRef {
    /// World-space vertex indices.
    pub vertices: [u32; 3],
    /// The instance it came from.
    pub instance: u32,
    /// Its surface shader.
    pub surface: u32,
}

/// A renderable scene. Camera, shaders, lights and sky may be changed freely after
/// construction; geometry is fixed (the BVH is built in [`Scene::new`]).
pub struct Scene<S, L> {
    /// The camera (its size is the image size).
    pub camera: Camera,
    /// Surface shaders, addressed by [`Instance::surface`].
    pub surfaces: Vec<S>,
    /// Light shaders.
    pub lights: Vec<L>,
    /// The named coordinate systems each surface shader sees (by [`Instance::surface`]); a
    /// surface without an entry sees [`Spaces::standard`]. Read only by shaders that name a
    /// space.
    pub surface_spaces: Vec<Spaces>,
    /// The lights each surface slot sees (by [`Instance::surface`]) when that is not every
    /// light of the scene: RenderMan's per-primitive light lists (`Illuminate`, lights
    /// declared inside an attribute block). A front end gives each distinct (surface shader,
    /// light list) its own slot. A slot without an entry, or with `None`, sees
    /// [`Scene::lights`].
    pub surface_lights: Vec<Option<Vec<L>>>,
    /// What escaping rays see.
    pub sky: Sky,
    instances: Vec<Instance>,
    positions: Vec<Vec3A>,
    normals: Vec<Vec3A>,
    uvs: Vec<Vec2>,
    // Per vertex, each empty unless some mesh has it: s and t, ∂P/∂u, ∂P/∂v (zero where the
    // triangle gives them), Cs and Os (the instance's where the mesh has none).
    st: Vec<Vec2>,
    dpdu: Vec<Vec3A>,
    dpdv: Vec<Vec3A>,
    cs: Vec<[f32; 3]>,
    os: Vec<[f32; 3]>,
    // Per instance: (Cs, Os) and whether it is one-sided.
    instance_colors: Vec<([f32; 3], [f32; 3])>,
    one_sided: Vec<bool>,
    any_one_sided: bool,
    /// Every surface is white and opaque (no vertex colours, every instance's `Cs` and `Os`
    /// one): shaders get constant `Cs`/`Os` without reading them from the hit records.
    pub(crate) all_white: bool,
    triangles: Vec<TriangleRef>,
    accel: Accel,
}

impl<S, L> Scene<S, L> {
    /// The lights the points of surface slot `surface` see ([`Scene::surface_lights`]).
    #[inline]
    #[must_use]
    pub fn lights_for(&self, surface: u32) -> &[L] {
        match self.surface_lights.get(surface as usize) {
            Some(Some(lights)) => lights,
            _ => &self.lights,
        }
    }

    /// Places `meshes` by `instances` in world space and builds the BVH.
    ///
    /// # Errors
    /// An instance that names a missing mesh or surface shader, or a mesh whose normal or
    /// texture-coordinate count differs from its position count.
    pub fn new(
        camera: Camera,
        meshes: &[Mesh],
        instances: Vec<Instance>,
        surfaces: Vec<S>,
        lights: Vec<L>,
    ) -> Result<Self, SceneError> {
        let (mut positions, mut normals, mut uvs, mut triangles) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let used = |f: &dyn Fn(&Mesh) -> bool| instances.iter().any(|i| meshes.get(i.mesh).is_some_and(f));
        let (with_st, with_dp) = (used(&|m| m.st.is_some()), used(&|m| m.dpdu_dpdv.is_some()));
        let with_colors = used(&|m| m.cs.is_some() || m.os.is_some());
        let (mut st, mut dpdu, mut dpdv, mut cs, mut os) = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (k, inst) in instances.iter().enumerate() {
            let mesh = meshes
                .get(inst.mesh)
                .ok_or_else(|| SceneError(format!("instance {k} uses mesh {} of {}", inst.mesh, meshes.len())))?;
            if inst.surface >= surfaces.len() {
                return Err(SceneError(format!("instance {k} uses surface {} of {}", inst.surface, surfaces.len())));
            }
            let count = mesh.positions.len();
            if mesh.normals.len() != count || mesh.uvs.len() != count {
                return Err(SceneError(format!(
                    "mesh {}: {} positions but {} normals and {} texture coordinates",
                    inst.mesh,
                    count,
                    mesh.normals.len(),
                    mesh.uvs.len()
                )));
            }
            let lengths = [
                ("s,t", mesh.st.as_ref().map(Vec::len)),
                ("dPdu", mesh.dpdu_dpdv.as_ref().map(|d| d.0.len())),
                ("dPdv", mesh.dpdu_dpdv.as_ref().map(|d| d.1.len())),
                ("Cs", mesh.cs.as_ref().map(Vec::len)),
                ("Os", mesh.os.as_ref().map(Vec::len)),
            ];
            if let Some((name, Some(n))) = lengths.iter().find(|(_, n)| n.is_some_and(|n| n != count)) {
                return Err(SceneError(format!("mesh {}: {count} positions but {n} values of {name}", inst.mesh)));
            }
            let base = positions.len() as u32;
            let normal_matrix = inst.transform.inverse().transpose();
            let sign = if inst.flip_normals { -1.0 } else { 1.0 };
            positions.extend(mesh.positions.iter().map(|p| Vec3A::from(inst.transform.transform_point3(*p))));
            normals.extend(
                mesh.normals
                    .iter()
                    .map(|n| Vec3A::from(normal_matrix.transform_vector3(*n)).normalize_or_zero() * sign),
            );
            uvs.extend_from_slice(&mesh.uvs);
            if with_st {
                st.extend_from_slice(mesh.st.as_deref().unwrap_or(&mesh.uvs));
            }
            if with_dp {
                let world = |v: &Vec3| Vec3A::from(inst.transform.transform_vector3(*v));
                match &mesh.dpdu_dpdv {
                    Some((du, dv)) => {
                        dpdu.extend(du.iter().map(world));
                        dpdv.extend(dv.iter().map(world));
                    }
                    None => {
                        dpdu.resize(positions.len(), Vec3A::ZERO);
                        dpdv.resize(positions.len(), Vec3A::ZERO);
                    }
                }
            }
            if with_colors {
                match &mesh.cs {
                    Some(c) => cs.extend_from_slice(c),
                    None => cs.resize(positions.len(), inst.color),
                }
                match &mesh.os {
                    Some(o) => os.extend_from_slice(o),
                    None => os.resize(positions.len(), inst.opacity),
                }
            }
            for tri in &mesh.triangles {
                if tri.iter().any(|&i| i as usize >= mesh.positions.len()) {
                    return Err(SceneError(format!("mesh {}: triangle {tri:?} indexes past its vertices", inst.mesh)));
                }
                triangles.push(TriangleRef {
                    vertices: tri.map(|i| base + i),
                    instance: k as u32,
                    surface: inst.surface as u32,
                });
            }
        }
        let world: Vec<[Vec3A; 3]> = triangles.iter().map(|t| t.vertices.map(|i| positions[i as usize])).collect();
        let accel = Accel::build(&world);
        let instance_colors = instances.iter().map(|i| (i.color, i.opacity)).collect();
        let one_sided: Vec<bool> = instances.iter().map(|i| !i.two_sided).collect();
        let any_one_sided = one_sided.iter().any(|&b| b);
        let all_white = cs.is_empty() && instances.iter().all(|i| i.color == [1.0; 3] && i.opacity == [1.0; 3]);
        Ok(Self {
            camera,
            surfaces,
            lights,
            surface_spaces: Vec::new(),
            surface_lights: Vec::new(),
            sky: Sky::default(),
            instances,
            positions,
            normals,
            uvs,
            st,
            dpdu,
            dpdv,
            cs,
            os,
            instance_colors,
            one_sided,
            any_one_sided,
            all_white,
            triangles,
            accel,
        })
    }

    /// Whether the hit is on the back of a one-sided instance (the side away from its
    /// shading normals, seen along `dir`).
    #[inline]
    fn culled(&self, hit: &Hit, dir: Vec3A) -> bool {
        let tri = &self.triangles[hit.prim as usize];
        self.one_sided[tri.instance as usize]
            && tri.vertices.iter().map(|&i| self.normals[i as usize]).sum::<Vec3A>().dot(dir) > 0.0
    }

    /// [`Scene::intersect`] for camera rays: the backs of one-sided instances are passed
    /// through.
    #[inline]
    #[must_use]
    pub fn intersect_camera(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        let mut t0 = tmin;
        loop {
            let hit = self.intersect(origin, dir, t0, tmax)?;
            if !self.any_one_sided || !self.culled(&hit, dir) || hit.t <= t0 {
                return Some(hit);
            }
            t0 = hit.t;
        }
    }

    /// [`Scene::intersect_packet`] for camera rays: the backs of one-sided instances are
    /// passed through (those lanes are traced again one by one).
    #[inline]
    pub fn intersect_packet_camera(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        let mut bits = self.intersect_packet(rays, out);
        if self.any_one_sided {
            for (i, hit) in out.iter_mut().enumerate() {
                if (bits >> i) & 1 != 0 && self.culled(hit, rays.dirs[i]) {
                    match self.intersect_camera(rays.origins[i], rays.dirs[i], hit.t, rays.tmax[i]) {
                        Some(h) => *hit = h,
                        None => bits &= !(1 << i),
                    }
                }
            }
        }
        bits
    }

    /// The instances.
    #[must_use]
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// The flattened triangles (index = [`Hit::prim`]).
    #[must_use]
    pub fn triangles(&self) -> &[TriangleRef] {
        &self.triangles
    }

    /// The world-space vertices of triangle `prim`.
    #[must_use]
    pub fn triangle_vertices(&self, prim: u32) -> [Vec3A; 3] {
        self.triangles[prim as usize].vertices.map(|i| self.positions[i as usize])
    }

    /// The BVH (and brute-force reference) over the triangles.
    #[must_use]
    pub fn accel(&self) -> &Accel {
        &self.accel
    }

    /// The closest hit along `origin + t · dir`, `tmin < t < tmax`.
    #[inline]
    #[must_use]
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        self.accel.closest_hit(origin, dir, tmin, tmax)
    }

    /// The closest hits of a packet of rays traced together ([`Accel::closest_hits`]): the
    /// bits of the rays that hit, their hits in `out`.
    #[inline]
    pub fn intersect_packet(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        self.accel.closest_hits(rays, out)
    }

    /// The shading record of `hit` on the ray `origin + t · dir`; with the camera ray's
    /// `differential` (how its origin and direction change from pixel to pixel) it also
    /// carries the screen-space derivatives of P, N, s and t.
    ///
    /// Inlined into its callers, so the record is built in the caller's slot: called, it was
    /// returned through a temporary that the caller copied with 64-byte moves, which read
    /// back the callee's narrower stores (a store-forwarding stall per hit).
    #[inline(always)]
    #[must_use]
    pub fn surface_hit(
        &self,
        hit: &Hit,
        origin: Vec3A,
        dir: Vec3A,
        differential: Option<RayDifferential>,
    ) -> SurfaceHit {
        let tri = &self.triangles[hit.prim as usize];
        let [i0, i1, i2] = tri.vertices.map(|i| i as usize);
        let (p0, p1, p2) = (self.positions[i0], self.positions[i1], self.positions[i2]);
        let (n0, n1, n2) = (self.normals[i0], self.normals[i1], self.normals[i2]);
        let (uv0, uv1, uv2) = (self.uvs[i0], self.uvs[i1], self.uvs[i2]);
        let (b1, b2) = (hit.b1, hit.b2);
        let b0 = 1.0 - b1 - b2;
        let (st0, st1, st2) =
            if self.st.is_empty() { (uv0, uv1, uv2) } else { (self.st[i0], self.st[i1], self.st[i2]) };
        let e1 = p1 - p0;
        let e2 = p2 - p0;
        let p = p0 * b0 + p1 * b1 + p2 * b2;
        let mut ng = e1.cross(e2).normalize_or_zero();
        let n_raw = n0 * b0 + n1 * b1 + n2 * b2;
        let n_len = n_raw.length();
        let n = if n_len > 0.0 { n_raw / n_len } else { ng };
        if ng.dot(n) < 0.0 {
            ng = -ng;
        }
        let uv = uv0 * b0 + uv1 * b1 + uv2 * b2;
        let st = st0 * b0 + st1 * b1 + st2 * b2;
        let (cs, os) = if self.cs.is_empty() {
            self.instance_colors[tri.instance as usize]
        } else {
            let mix = |c: &[[f32; 3]]| {
                let (c0, c1, c2) = (Vec3A::from(c[i0]), Vec3A::from(c[i1]), Vec3A::from(c[i2]));
                (c0 * b0 + c1 * b1 + c2 * b2).to_array()
            };
            (mix(&self.cs), mix(&self.os))
        };

        // ∂P/∂u, ∂P/∂v from the triangle's (s, t) parameterization (pbrt's construction).
        let duv02 = uv0 - uv2;
        let duv12 = uv1 - uv2;
        let dp02 = p0 - p2;
        let dp12 = p1 - p2;
        let det = duv02.x * duv12.y - duv02.y * duv12.x;
        let exact = if self.dpdu.is_empty() {
            None
        } else {
            let du = self.dpdu[i0] * b0 + self.dpdu[i1] * b1 + self.dpdu[i2] * b2;
            let dv = self.dpdv[i0] * b0 + self.dpdv[i1] * b1 + self.dpdv[i2] * b2;
            (du.length_squared() > 0.0 || dv.length_squared() > 0.0).then_some((du, dv))
        };
        let (dpdu, dpdv) = if let Some(exact) = exact {
            exact
        } else if det.abs() > 1e-12 {
            let inv = 1.0 / det;
            ((dp02 * duv12.y - dp12 * duv02.y) * inv, (dp12 * duv02.x - dp02 * duv12.x) * inv)
        } else {
            let a = ng.any_orthonormal_vector();
            (a, ng.cross(a))
        };

        let mut sh = SurfaceHit {
            p,
            n,
            ng,
            i: p - origin,
            e: origin,
            s: st.x,
            t: st.y,
            u: uv.x,
            v: uv.y,
            cs,
            os,
            dpdu,
            dpdv,
            surface: tri.surface,
            ..SurfaceHit::default()
        };

        if let Some(rd) = differential {
            // The offset rays meet the tangent plane at p + dP/dx, p + dP/dy.
            let transfer = |dorigin: Vec3A, dd: Vec3A| {
                let (origin2, dir2) = (origin + dorigin, dir + dd);
                let denom = ng.dot(dir2);
                if denom.abs() < 1e-12 {
                    Vec3A::ZERO
                } else {
                    origin2 + dir2 * (ng.dot(p - origin2) / denom) - p
                }
            };
            let (dpdx, dpdy) = (transfer(rd.dodx, rd.ddx), transfer(rd.dody, rd.ddy));
            // Barycentric derivatives: dP = db1·e1 + db2·e2 (least squares in the plane).
            let (a11, a12, a22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
            let gdet = a11 * a22 - a12 * a12;
            let bary = |dp: Vec3A| -> (f32, f32) {
                if gdet.abs() < 1e-30 {
                    return (0.0, 0.0);
                }
                let (r1, r2) = (e1.dot(dp), e2.dot(dp));
                ((a22 * r1 - a12 * r2) / gdet, (a11 * r2 - a12 * r1) / gdet)
            };
            let (db1x, db2x) = bary(dpdx);
            let (db1y, db2y) = bary(dpdy);
            let (duv1, duv2) = (uv1 - uv0, uv2 - uv0);
            let dn1 = n1 - n0;
            let dn2 = n2 - n0;
            let dnorm = |dn_raw: Vec3A| {
                if n_len > 0.0 {
                    (dn_raw - n * n.dot(dn_raw)) / n_len
                } else {
                    Vec3A::ZERO
                }
            };
            sh.dpdx = dpdx;
            sh.dpdy = dpdy;
            sh.dndx = dnorm(dn1 * db1x + dn2 * db2x);
            sh.dndy = dnorm(dn1 * db1y + dn2 * db2y);
            let (dst1, dst2) = (st1 - st0, st2 - st0);
            sh.dsdx = dst1.x * db1x + dst2.x * db2x;
            sh.dsdy = dst1.x * db1y + dst2.x * db2y;
            sh.dtdx = dst1.y * db1x + dst2.y * db2x;
            sh.dtdy = dst1.y * db1y + dst2.y * db2y;
            if self.st.is_empty() {
                sh.du = sh.dsdx.abs().max(sh.dsdy.abs());
                sh.dv = sh.dtdx.abs().max(sh.dtdy.abs());
            } else {
                let (dudx, dudy) = (duv1.x * db1x + duv2.x * db2x, duv1.x * db1y + duv2.x * db2y);
                let (dvdx, dvdy) = (duv1.y * db1x + duv2.y * db2x, duv1.y * db1y + duv2.y * db2y);
                sh.du = dudx.abs().max(dudy.abs());
                sh.dv = dvdx.abs().max(dvdy.abs());
            }
        }
        sh
    }
}

/// Everything a surface shader sees at one hit, in world space, plus the screen-space
/// derivative seeds (zero for rays without differentials). `u`, `v` are the mesh's surface
/// parameters; `s`, `t` its texture coordinates (the same unless the mesh has its own).
/// `repr(C)`, every field 4-byte floats (or the `u32` shader index): the packet renderer
/// transposes these records with vector shuffles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SurfaceHit {
    /// Position.
    pub p: Vec3A,
    /// Interpolated, normalized shading normal.
    pub n: Vec3A,
    /// Geometric normal (unit, on the side of `n`).
    pub ng: Vec3A,
    /// Incident vector `p - e`.
    pub i: Vec3A,
    /// Ray origin.
    pub e: Vec3A,
    /// Texture coordinate s.
    pub s: f32,
    /// Texture coordinate t.
    pub t: f32,
    /// RSL `du`: the larger of |∂s/∂x|, |∂s/∂y|.
    pub du: f32,
    /// RSL `dv`: the larger of |∂t/∂x|, |∂t/∂y|.
    pub dv: f32,
    /// ∂P/∂u.
    pub dpdu: Vec3A,
    /// ∂P/∂v.
    pub dpdv: Vec3A,
    /// ∂P/∂x (screen space; also ∂I/∂x for a fixed eye).
    pub dpdx: Vec3A,
    /// ∂P/∂y.
    pub dpdy: Vec3A,
    /// ∂N/∂x.
    pub dndx: Vec3A,
    /// ∂N/∂y.
    pub dndy: Vec3A,
    /// ∂s/∂x.
    pub dsdx: f32,
    /// ∂s/∂y.
    pub dsdy: f32,
    /// ∂t/∂x.
    pub dtdx: f32,
    /// ∂t/∂y.
    pub dtdy: f32,
    /// Surface parameter u.
    pub u: f32,
    /// Surface parameter v.
    pub v: f32,
    /// Surface colour `Cs`.
    pub cs: [f32; 3],
    /// Surface opacity `Os`.
    pub os: [f32; 3],
    /// Surface shader index.
    pub surface: u32,
}
