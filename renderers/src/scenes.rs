//! The embedded scenes. Each takes the surface shader(s) and lights as arguments, so scene
//! construction stays separate from shader choice (the `anysl` CLI pairs them).

use crate::camera::Camera;
use crate::mesh::Mesh;
use crate::scene::{Instance, Scene, Sky};
use glam::{Mat4, Quat, Vec3, Vec3A};

/// The Stanford bunny (low resolution, 3 674 triangles), embedded.
pub const BUNNY_OBJ: &str = include_str!("../assets/bunny.obj");

/// The embedded bunny as a mesh (object space: y up, about 9.7 units tall, standing on y = 0).
///
/// # Panics
/// Never for the embedded file (its parse is tested).
#[must_use]
pub fn bunny_mesh() -> Mesh {
    Mesh::from_obj(BUNNY_OBJ, "assets/bunny.obj").expect("the embedded bunny parses")
}

/// The AnySL paper's Table 1 setup (and `shaders/assets/workload_ref/shading_workload.md`): one
/// triangulated unit sphere (64 × 32 segments) at the origin, seen from (0, 0, 3) looking at
/// the origin with a vertical field of view of 2·atan(0.375), `size × size` pixels (512 in
/// the paper), black background. The workload's two point lights come from the shader
/// collection (`table1_lights()`); the workload has no shadows, so render it with
/// `RenderOptions { shadows: false, .. }` to match it exactly.
#[must_use]
pub fn table1<S, L>(surface: S, lights: Vec<L>, size: u32) -> Scene<S, L> {
    let camera = Camera::new(Vec3A::new(0.0, 0.0, 3.0), Vec3A::ZERO, Vec3A::Y, 2.0 * 0.375f32.atan(), size, size);
    let sphere = Mesh::uv_sphere(1.0, 64, 32);
    let instances = vec![Instance::new(0, 0, Mat4::IDENTITY)];
    Scene::new(camera, &[sphere], instances, vec![surface], lights).expect("the table-1 scene is well formed")
}

/// Ten shaders side by side: a 5 × 2 grid of spheres (radius 0.4) on a ground plane with
/// the bunny in front; `size` pixels wide, 9/16 as high, sky visible.
///
/// `surfaces[0..10]` shade the spheres (back row left to right, then the front row). The
/// bunny uses `surfaces[10]` and the ground `surfaces[11]` when given; otherwise the bunny
/// shares sphere 0's shader and the ground sphere 9's.
///
/// # Panics
/// When fewer than 10 surfaces are given.
#[must_use]
pub fn gallery<S, L>(surfaces: Vec<S>, lights: Vec<L>, size: u32) -> Scene<S, L> {
    assert!(surfaces.len() >= 10, "the gallery needs 10 surface shaders, got {}", surfaces.len());
    let height = (size * 9 / 16).max(1);
    let camera = Camera::new(Vec3A::new(0.0, 2.4, 5.2), Vec3A::new(0.0, 0.25, -0.3), Vec3A::Y, 0.62, size, height);
    let meshes = [Mesh::uv_sphere(1.0, 48, 24), bunny_mesh(), Mesh::ground_quad(1.0, 8.0)];
    let mut instances = Vec::with_capacity(12);
    for k in 0..10 {
        let (col, row) = ((k % 5) as f32, (k / 5) as f32);
        let centre = Vec3::new((col - 2.0) * 1.05, 0.4, -1.1 + row * 1.0);
        instances.push(Instance::new(
            0,
            k,
            Mat4::from_scale_rotation_translation(Vec3::splat(0.4), Quat::IDENTITY, centre),
        ));
    }
    let bunny_surface = if surfaces.len() > 10 { 10 } else { 0 };
    let ground_surface = if surfaces.len() > 11 { 11 } else { 9 };
    instances.push(Instance::new(
        1,
        bunny_surface,
        Mat4::from_scale_rotation_translation(Vec3::splat(0.07), Quat::IDENTITY, Vec3::new(0.0, 0.0, 1.0)),
    ));
    instances.push(Instance::new(2, ground_surface, Mat4::from_scale(Vec3::new(8.0, 1.0, 8.0))));
    let mut scene = Scene::new(camera, &meshes, instances, surfaces, lights).expect("the gallery scene is well formed");
    scene.sky = Sky { visible_to_camera: true, ..Sky::default() };
    scene
}

/// The bunny alone with one shader, scaled to unit height and centred at the origin, seen
/// from the front-right; `size × size` pixels, black background.
#[must_use]
pub fn bunny<S, L>(surface: S, lights: Vec<L>, size: u32) -> Scene<S, L> {
    let mesh = bunny_mesh();
    let (lo, hi) = mesh.bounds();
    let scale = 1.0 / (hi.y - lo.y);
    let centre = (lo + hi) * 0.5;
    let transform = Mat4::from_scale(Vec3::splat(scale)) * Mat4::from_translation(-centre);
    let camera = Camera::new(Vec3A::new(0.6, 0.35, 2.2), Vec3A::new(0.0, -0.02, 0.0), Vec3A::Y, 0.55, size, size);
    let instances = vec![Instance::new(0, 0, transform)];
    Scene::new(camera, &[mesh], instances, vec![surface], lights).expect("the bunny scene is well formed")
}
