//! The built-in scenes: the embedded files are those of data/scenes and load identically from
//! disk; each has the documented camera, and its light and content where data/scenes/README.md
//! says (the point-light scenes: a closed room around its light, and chess-spot's board under a
//! point light above the pieces).

use glam::{DMat4, DVec3};
use shadowlab_hull::{NdcDepth, light_view_angle};
use shadowlab_scene::{
    BUILTIN_SCENES, Bounds, DEFAULT_SCENE, Scene, SceneLight, builtin_scene, builtin_scene_text,
    load_scene,
};

use crate::support::data_path;

fn scene(name: &str) -> Scene {
    builtin_scene(name).unwrap_or_else(|error| panic!("{name}: {error}"))
}

#[test]
fn the_built_ins_are_the_files_of_data_scenes() {
    let mut on_disk: Vec<String> = std::fs::read_dir(data_path("scenes"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .map(|path| path.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let mut builtin = BUILTIN_SCENES.map(str::to_owned).to_vec();
    builtin.sort();
    assert_eq!(builtin, on_disk);
    assert!(BUILTIN_SCENES.contains(&DEFAULT_SCENE));
    assert_eq!(builtin_scene_text("nowhere"), None);
}

#[test]
fn embedded_and_on_disk_are_identical() {
    for name in BUILTIN_SCENES {
        let path = data_path(&format!("scenes/{name}.toml"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(builtin_scene_text(name), Some(text.as_str()), "{name}");
        // Scene files are ASCII, so that mangling them byte by byte keeps them UTF-8.
        assert!(text.is_ascii(), "{name}");
        let from_disk = load_scene(&path).unwrap_or_else(|error| panic!("{error}"));
        assert_eq!(scene(name), from_disk, "{name}");
        assert_eq!(from_disk.name, name);
    }
}

/// The bounds of the triangles of the group named `group`.
fn group_bounds(scene: &Scene, group: &str) -> Bounds {
    let id = scene
        .mesh
        .group_names()
        .iter()
        .position(|name| name == group)
        .unwrap_or_else(|| panic!("{}: no group {group}", scene.name));
    let mut bounds: Option<Bounds> = None;
    for t in 0..scene.mesh.triangle_count() {
        if scene.mesh.groups()[t] as usize != id {
            continue;
        }
        for p in scene.mesh.triangle_positions(t) {
            let b = bounds.get_or_insert(Bounds { min: p, max: p });
            b.min = b.min.min(p);
            b.max = b.max.max(p);
        }
    }
    bounds.expect("a group with triangles")
}

/// The camera's view-projection matrix (GL clip space).
fn clip_from_world(scene: &Scene) -> DMat4 {
    scene.camera.view_projection(NdcDepth::NegativeOneToOne)
}

/// Whether `p` is inside the clip volume of `m`.
fn in_view(m: &DMat4, p: DVec3) -> bool {
    let c = *m * p.extend(1.0);
    c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w && c.z.abs() <= c.w
}

/// The eye depth of `p` along the camera's view direction.
fn depth(scene: &Scene, p: DVec3) -> f64 {
    (p - scene.camera.pose.eye()).dot(scene.camera.pose.forward())
}

/// The unit vector toward the scene's first light, which must be directional.
fn to_light(scene: &Scene) -> DVec3 {
    match &scene.lights[..] {
        [SceneLight::Directional { to_light }] => *to_light,
        other => panic!(
            "{}: one directional light expected, got {other:?}",
            scene.name
        ),
    }
}

/// The elevation of a directional light above the ground (y = 0), in degrees.
fn elevation(to_light: DVec3) -> f64 {
    to_light.y.asin().to_degrees()
}

/// γ between the camera's view direction and the first light, in degrees.
fn gamma(scene: &Scene) -> f64 {
    light_view_angle(scene.camera.pose.forward(), to_light(scene))
        .unwrap()
        .to_degrees()
}

/// Asserts the camera's field of view (degrees), near and far, and image size 1024 × 768.
fn assert_camera(scene: &Scene, fov_degrees: f64, near: f64, far: f64) {
    let projection = scene.camera.projection;
    assert!(
        (projection.fov_y().to_degrees() - fov_degrees).abs() < 1e-12,
        "{}: fov {}",
        scene.name,
        projection.fov_y().to_degrees()
    );
    assert_eq!(
        (projection.near(), projection.far()),
        (near, far),
        "{}",
        scene.name
    );
    assert_eq!((scene.camera.width, scene.camera.height), (1024, 768));
}

#[test]
fn every_entry_of_every_built_in_can_be_seen() {
    for name in BUILTIN_SCENES {
        let scene = scene(name);
        let m = clip_from_world(&scene);
        let mut seen = vec![false; scene.mesh.group_count()];
        for t in 0..scene.mesh.triangle_count() {
            if scene
                .mesh
                .triangle_positions(t)
                .iter()
                .any(|&p| in_view(&m, p))
            {
                seen[scene.mesh.groups()[t] as usize] = true;
            }
        }
        for (group, seen) in scene.mesh.group_names().iter().zip(seen) {
            assert!(seen, "{name}: no vertex of {group} is in view");
        }
    }
}

#[test]
fn outdoor_is_lispsm_s_set_up() {
    let scene = scene("outdoor");
    assert_camera(&scene, 60.0, 1.0, 400.0);
    assert_eq!(scene.camera.pose.eye(), DVec3::new(0.0, 1.8, 0.0));
    // Looking along the ground.
    assert!(scene.camera.pose.forward().y.abs() < 0.01);
    // A sun from the side: nearly perpendicular to the view, 30–45° above the ground.
    let gamma = gamma(&scene);
    assert!((80.0..=90.0).contains(&gamma), "γ = {gamma}");
    let elevation = elevation(to_light(&scene));
    assert!((30.0..=45.0).contains(&elevation), "elevation {elevation}");
    // The ground reaches past the far plane, across the whole width of the view there.
    let ground = group_bounds(&scene, "ground");
    let tan_half_x = scene.camera.projection.tan_half_fov_y() * scene.camera.projection.aspect();
    assert!(ground.min.z < -400.0 && ground.max.z > 0.0);
    assert!(ground.min.x < -400.0 * tan_half_x && ground.max.x > 400.0 * tan_half_x);
    // Poles and boxes recede to the far plane: the farthest lies between 350 and 400.
    for group in ["poles-left", "poles-right", "boxes-left", "boxes-right"] {
        let bounds = group_bounds(&scene, group);
        let farthest = depth(&scene, DVec3::new(0.0, 1.0, bounds.min.z));
        assert!((350.0..400.0).contains(&farthest), "{group}: {farthest}");
    }
    // The poles are thin: 0.2 across.
    let pole = group_bounds(&scene, "poles-left");
    assert!(pole.size().x <= 0.2 + 1e-12);
    // The bunny stands near the camera.
    let bunny = group_bounds(&scene, "bunny");
    assert!(depth(&scene, bunny.max) < 10.0 && depth(&scene, bunny.min) > 1.0);
}

#[test]
fn dueling_frusta_shines_toward_the_camera() {
    let scene = scene("dueling-frusta");
    assert_camera(&scene, 60.0, 1.0, 300.0);
    let to_light = to_light(&scene);
    // The light is in front of the camera: the light vector points forward, so the light
    // travels toward the viewer, 15–20° from anti-parallel to the view direction.
    assert!(to_light.dot(scene.camera.pose.forward()) > 0.0);
    let gamma = gamma(&scene);
    assert!((15.0..=20.0).contains(&gamma), "γ = {gamma}");
    // Low: long shadows.
    let elevation = elevation(to_light);
    assert!((5.0..=15.0).contains(&elevation), "elevation {elevation}");
}

#[test]
fn cad_lattice_spreads_thin_bars_from_near_to_far() {
    let scene = scene("cad-lattice");
    assert_camera(&scene, 60.0, 1.0, 800.0);
    let gamma = gamma(&scene);
    assert!((50.0..=60.0).contains(&gamma), "γ = {gamma}");
    let near = group_bounds(&scene, "scaffold-near");
    assert!(depth(&scene, near.max) < 10.0, "a lattice a few units away");
    let towers = group_bounds(&scene, "towers");
    let rails = group_bounds(&scene, "rails");
    for far in [towers, rails] {
        let farthest = depth(&scene, DVec3::new(0.0, 0.0, far.min.z));
        assert!((600.0..800.0).contains(&farthest), "{farthest}");
    }
    // The bars are thin next to the lattices' cells.
    assert!(near.size().x > 100.0 * 0.04);
    assert!(rails.size().y <= 0.06 + 1e-12);
}

#[test]
fn chess_spot_is_lit_by_a_spot_light_above_the_board() {
    let scene = scene("chess-spot");
    assert_camera(&scene, 60.0, 1.0, 30.0);
    let [SceneLight::Spot { pose, cone }] = &scene.lights[..] else {
        panic!("one spot light: {:?}", scene.lights);
    };
    assert_eq!(pose.eye(), DVec3::new(2.0, 12.0, 2.0));
    assert!(pose.forward().y < -0.9, "shining down: {}", pose.forward());
    assert!((cone.fov_y().to_degrees() - 70.0).abs() < 1e-12);
    assert_eq!((cone.near(), cone.far()), (2.0, 30.0));
    // The spot's frustum holds the board and every piece (the table's edges may be outside).
    let frustum = scene.lights[0].light().frustum().unwrap().clone();
    for t in 0..scene.mesh.triangle_count() {
        let group = &scene.mesh.group_names()[scene.mesh.groups()[t] as usize];
        if group != "table" {
            for p in scene.mesh.triangle_positions(t) {
                assert!(frustum.contains(p, 0.0), "{group}: {p} is not lit");
            }
        }
    }
    // The board is the 8 × 8 squares of side 1 with a frame of 0.5.
    let board = group_bounds(&scene, "board");
    assert_eq!(board.min, DVec3::new(-4.5, 0.0, -4.5));
    assert_eq!(board.max, DVec3::new(4.5, 0.0, 4.5));
}

#[test]
fn bunny_is_lit_from_above_at_an_angle() {
    let scene = scene("bunny");
    assert_camera(&scene, 45.0, 1.0, 100.0);
    let to_light = to_light(&scene);
    let elevation = elevation(to_light);
    assert!((45.0..=60.0).contains(&elevation), "elevation {elevation}");
    // The whole bunny is in view, standing on the plane.
    let m = clip_from_world(&scene);
    let bunny = group_bounds(&scene, "bunny");
    for t in 0..scene.mesh.triangle_count() {
        if scene.mesh.group_names()[scene.mesh.groups()[t] as usize] == "bunny" {
            for p in scene.mesh.triangle_positions(t) {
                assert!(in_view(&m, p), "{p}");
            }
        }
    }
    let ground = group_bounds(&scene, "ground");
    assert!((bunny.min.y - ground.max.y).abs() < 0.01);
}

/// The distance along `direction` (unit) from `origin` to the nearest triangle of the groups
/// named in `groups` (Möller–Trumbore, both faces), if any is hit.
fn ray_hit(scene: &Scene, groups: &[&str], origin: DVec3, direction: DVec3) -> Option<f64> {
    let names = scene.mesh.group_names();
    let mut nearest: Option<f64> = None;
    for t in 0..scene.mesh.triangle_count() {
        if !groups.contains(&names[scene.mesh.groups()[t] as usize].as_str()) {
            continue;
        }
        let [a, b, c] = scene.mesh.triangle_positions(t);
        let (e1, e2) = (b - a, c - a);
        let p = direction.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-12 {
            continue;
        }
        let s = origin - a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = direction.dot(q) / det;
        let distance = e2.dot(q) / det;
        if (-1e-9..=1.0 + 1e-9).contains(&u) && v >= -1e-9 && u + v <= 1.0 + 1e-9 && distance > 0.0
        {
            nearest = Some(nearest.map_or(distance, |n: f64| n.min(distance)));
        }
    }
    nearest
}

/// `count` unit vectors spread evenly over the sphere (a Fibonacci lattice).
fn sphere_directions(count: u32) -> impl Iterator<Item = DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5_f64.sqrt());
    (0..count).map(move |k| {
        let y = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(count);
        let r = (1.0 - y * y).sqrt();
        let phi = golden * f64::from(k);
        DVec3::new(r * phi.cos(), y, r * phi.sin())
    })
}

/// The shell of room-point: the groups that close the room.
const ROOM_SHELL: [&str; 4] = ["floor", "ceiling", "side-walls", "end-walls"];

#[test]
fn room_point_is_a_closed_room_lit_by_a_point_light_among_its_furniture() {
    let scene = scene("room-point");
    assert_camera(&scene, 60.0, 0.5, 12.0);
    let [SceneLight::Point { position, range }] = scene.lights[..] else {
        panic!("one point light: {:?}", scene.lights);
    };
    assert_eq!(position, DVec3::new(0.0, 2.5, -0.5));
    assert_eq!(range, Some(8.0));
    assert_eq!(scene.lights[0].light().position(), Some(position));
    // The camera and the light are inside the room (inner faces at x = ±4, y = 0 and 3,
    // z = ±5), the light 0.5 below the ceiling and near the middle.
    let inside = |p: DVec3| p.x.abs() < 4.0 && p.y > 0.0 && p.y < 3.0 && p.z.abs() < 5.0;
    assert!(inside(scene.camera.pose.eye()) && inside(position));
    assert!(position.x.abs() <= 1.0 && position.z.abs() <= 1.0);
    // Closed: every ray from the light meets the shell, within the light's range, so nothing
    // leaks out and the range lights every wall.
    let mut farthest: f64 = 0.0;
    for direction in sphere_directions(2000) {
        let hit = ray_hit(&scene, &ROOM_SHELL, position, direction)
            .unwrap_or_else(|| panic!("a ray from the light along {direction} leaves the room"));
        farthest = farthest.max(hit);
    }
    assert!(
        (6.5..8.0).contains(&farthest),
        "the farthest wall point hit {farthest}"
    );
    // The farthest points of the room, the lower corners of the near wall, are √52.5 ≈ 7.2
    // away: in range.
    let corner_distance = |k: i32| {
        let sign = |bit: i32| if k & bit == 0 { -1.0 } else { 1.0 };
        let corner = DVec3::new(4.0 * sign(1), 1.5 + 1.5 * sign(2), 5.0 * sign(4));
        (corner - position).length()
    };
    let farthest_corner = (0..8).map(corner_distance).fold(0.0, f64::max);
    assert_eq!(farthest_corner, 52.5_f64.sqrt());
    // Every piece of furniture is below the light; the cord hangs above it, not touching it.
    let names = scene.mesh.group_names();
    let furniture: Vec<&str> = names
        .iter()
        .map(String::as_str)
        .filter(|name| !ROOM_SHELL.contains(name) && *name != "pendant-cord")
        .collect();
    assert!(furniture.len() >= 10, "{furniture:?}");
    for name in &furniture {
        let bounds = group_bounds(&scene, name);
        assert!(
            bounds.max.y < position.y - 0.4,
            "{name} reaches {}",
            bounds.max.y
        );
        // Standing on the floor is inside.
        let above_floor = bounds.min + DVec3::new(0.0, 1e-9, 0.0);
        assert!(
            inside(above_floor) && inside(bounds.max),
            "{name} is not inside the room"
        );
    }
    let cord = group_bounds(&scene, "pendant-cord");
    assert!(cord.min.y > position.y && cord.min.y - position.y < 0.1);
    assert!(
        (cord.max.y - 3.0).abs() < 1e-12,
        "the cord hangs from the ceiling"
    );
    // Shadows fall in all directions: furniture stands in each quadrant around the light.
    let mut quadrants = [false; 4];
    for name in &furniture {
        let centre = group_bounds(&scene, name).centre() - position;
        quadrants[usize::from(centre.x > 0.0) + 2 * usize::from(centre.z > 0.0)] = true;
    }
    assert_eq!(quadrants, [true; 4]);
    // Thin objects: a pole, legs and slats at most 0.05 across.
    for (name, across) in [
        ("lamp-pole", 0.024),
        ("chair-legs-front", 0.035),
        ("screen-slats", 0.02),
        ("table-legs-back", 0.05),
    ] {
        let size = group_bounds(&scene, name).size();
        assert!(size.x.min(size.z) <= across + 1e-12, "{name}: {size}");
    }
    // Modest: a few thousand triangles.
    assert!(
        scene.mesh.triangle_count() < 2000,
        "{}",
        scene.mesh.triangle_count()
    );
}

#[test]
fn chess_point_is_chess_spot_under_a_point_light_above_the_pieces() {
    let point = scene("chess-point");
    let spot = scene("chess-spot");
    assert_eq!(point.camera, spot.camera);
    assert_eq!(point.mesh, spot.mesh);
    let [SceneLight::Point { position, range }] = point.lights[..] else {
        panic!("one point light: {:?}", point.lights);
    };
    assert_eq!((position, range), (DVec3::new(2.5, 3.5, 1.5), None));
    // Above the tallest piece by 2, over the board but off its centre.
    let tallest = point
        .mesh
        .group_names()
        .iter()
        .filter(|name| *name != "board" && *name != "table")
        .map(|name| group_bounds(&point, name).max.y)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!((tallest - 1.5).abs() < 1e-12, "{tallest}");
    assert!(position.y - tallest >= 2.0);
    assert!(position.x.abs() < 4.0 && position.z.abs() < 4.0);
    assert!(position.x.hypot(position.z) > 2.5);
    // In front of the camera, inside its view.
    assert!(in_view(&clip_from_world(&point), position));
}
