//! Unit tests of the silhouette scorer on hand-computed cases.

use std::f32::consts::FRAC_PI_2;

use glam::{Affine3A, Mat4, Vec2, Vec3, Vec4, vec2, vec3};
use image::{DynamicImage, GrayImage, Luma};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::raster::{Coverage, MAX_POLYGON, clip_triangle, convex_hull};
use super::*;
use crate::geometry::{CUBE, Instance, MeshLibrary};
use crate::score::form::{Form, smoothstep};
use crate::score::retained::WithFootprints;
use crate::score::scorer::Scorer;

const SMOOTH: Form = Form::Smooth {
    good: 1.0,
    bad: 1.0,
};
const WEIGHTED: Form = Form::Weighted { overlap: 0.0 };

fn orbit(phi: f32, theta: f32, radius: f32, fov: f32, near: f32, far: f32) -> OrbitCamera {
    OrbitCamera {
        phi,
        theta,
        radius,
        lookat: Vec3::ZERO,
        fov_degrees: fov,
        near,
        far,
    }
}

/// A camera that maps world space to clip space unchanged (orthographic, `w = 1`).
const IDENTITY: Camera = Camera::Matrices {
    view: Mat4::IDENTITY,
    projection: Mat4::IDENTITY,
};

/// Target pixels weigh 1, the others -1.
const MASK: Weighting = Weighting::mask(1.0, -1.0);

/// Black weighs 1, white -1.
const MAP: Weighting = Weighting::weight_map(1.0, -1.0);

fn white(width: u32, height: u32) -> DynamicImage {
    DynamicImage::ImageLuma8(GrayImage::from_pixel(width, height, Luma([255])))
}

fn cube_scorer(target: ImageTarget, form: Form) -> SilhouetteScorer {
    let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
    SilhouetteScorer::new(vec![target], &meshes, form).unwrap()
}

fn cube(scale: Vec3, at: Vec3) -> Instance {
    Instance {
        transform: Affine3A::from_scale_rotation_translation(scale, glam::Quat::IDENTITY, at),
        mesh: CUBE,
    }
}

fn covered(scorer: &SilhouetteScorer, model: &[Instance]) -> Vec<(u32, u32)> {
    let t = &scorer.targets()[0];
    let mut mask = vec![false; (t.width() * t.height()) as usize];
    scorer.coverage_mask(0, model, &mut mask).unwrap();
    (0..t.height())
        .flat_map(|y| (0..t.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| mask[(y * t.width() + x) as usize])
        .collect()
}

fn block(cols: std::ops::Range<u32>, rows: std::ops::Range<u32>) -> Vec<(u32, u32)> {
    rows.flat_map(|y| cols.clone().map(move |x| (x, y)))
        .collect()
}

#[test]
fn orbit_camera_matches_hand_computed_matrices() {
    // phi = theta = 0: w = (-1, 0, 0), v = (0, 1, 0), u = v x w = (0, 0, 1),
    // eye = (5, 0, 0). fov 90: s2 = 1; aspect 2: s1 = 0.5; near 1, far 3: z1 = 2,
    // z2 = -3.
    let camera = orbit(0.0, 0.0, 5.0, 90.0, 1.0, 3.0);
    assert!(camera.eye().abs_diff_eq(vec3(5.0, 0.0, 0.0), 1e-6));
    let view = Mat4::from_cols_array_2d(&[
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 5.0, 1.0],
    ]);
    assert!(camera.view().abs_diff_eq(view, 1e-6), "{}", camera.view());
    let projection = Mat4::from_cols_array_2d(&[
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 2.0, 1.0],
        [0.0, 0.0, -3.0, 0.0],
    ]);
    assert!(camera.projection(2.0).abs_diff_eq(projection, 1e-6));
    let vp = Camera::Orbit(camera).view_projection(200, 100);
    // (0, 1, 2) is 5 in front, 2 along u, 1 along v: clip (1, 1, 2 * 5 - 3, 5).
    let clip = vp * Vec4::new(0.0, 1.0, 2.0, 1.0);
    assert!(
        clip.abs_diff_eq(Vec4::new(1.0, 1.0, 7.0, 5.0), 1e-5),
        "{clip}"
    );
    // A point on the near plane (1 in front) has z = -w.
    let clip = vp * Vec4::new(4.0, 0.0, 0.0, 1.0);
    assert!(
        clip.abs_diff_eq(Vec4::new(0.0, 0.0, -1.0, 1.0), 1e-5),
        "{clip}"
    );
}

#[test]
fn orbit_camera_raised_and_turned() {
    // phi = 90 degrees, theta = 30 degrees: w = -(0, 1/2, sqrt3/2),
    // v = (0, sqrt3/2, -1/2), u = v x w = (-1, 0, 0), eye = 2 * -w.
    let (s, c) = (0.5f32, 0.866_025_4f32);
    let camera = orbit(FRAC_PI_2, 30f32.to_radians(), 2.0, 60.0, 0.1, 10.0);
    let view = camera.view();
    let rows = [view.row(0), view.row(1), view.row(2), view.row(3)];
    let eye = vec3(0.0, 2.0 * s, 2.0 * c);
    assert!(camera.eye().abs_diff_eq(eye, 1e-6));
    assert!(rows[0].abs_diff_eq(Vec4::new(-1.0, 0.0, 0.0, 0.0), 1e-6));
    assert!(rows[1].abs_diff_eq(Vec4::new(0.0, c, -s, 0.0), 1e-6));
    assert!(rows[2].abs_diff_eq(Vec4::new(0.0, -s, -c, 2.0), 1e-6));
    assert_eq!(rows[3], Vec4::W);
    let p = camera.projection(1.5);
    let s2 = 1.0 / 30f32.to_radians().tan();
    assert!((p.row(0).x - s2 / 1.5).abs() < 1e-6 && (p.row(1).y - s2).abs() < 1e-6);
    assert!((p.row(2).z - 10.1 / 9.9).abs() < 1e-6);
    assert!((p.row(2).w + 2.0 / 9.9).abs() < 1e-6);
    assert_eq!(p.row(3), Vec4::Z);
}

#[test]
fn unit_cube_head_on_covers_the_hand_computed_block() {
    // The camera at (0, 0, -5) looks along +z (phi = -90 degrees). The cube's front face
    // is 4.5 away and spans +-0.5: ndc +-1/9 with fov 90, pixels 50 +- 5.56 in a
    // 100 x 100 image, so the centres 44.5 ..= 55.5: columns and rows 44 to 55.
    let camera = Camera::Orbit(orbit(-FRAC_PI_2, 0.0, 5.0, 90.0, 0.1, 100.0));
    let target = ImageTarget::new("t".into(), &white(100, 100), camera, MASK).unwrap();
    let scorer = cube_scorer(target, SMOOTH);
    let model = [cube(Vec3::ONE, Vec3::ZERO)];
    assert_eq!(covered(&scorer, &model), block(44..56, 44..56));
    let counts = scorer.count(&model, &mut scorer.scratch()).targets()[0];
    assert_eq!(
        (counts.covered, counts.on_target, counts.off_target),
        (144, 0, 144)
    );
    assert_eq!(counts.level_sum, 144 * 255);
    // World +x lands to the right, +y up. The cube moved by (2, 1, 0) has its front face
    // 4.5 away (x in [1.5, 2.5] -> pixels 66.7 to 77.8, y in [0.5, 1.5] -> 33.3 to 44.4)
    // and its back face 5.5 away (pixels 63.6 to 72.7 and 36.4 to 45.5): the silhouette
    // spans the centres of columns 64 to 77 and rows 33 to 44.
    let pixels = covered(&scorer, &[cube(Vec3::ONE, vec3(2.0, 1.0, 0.0))]);
    let cols = pixels.iter().map(|p| p.0);
    let rows = pixels.iter().map(|p| p.1);
    assert_eq!((cols.clone().min(), cols.max()), (Some(64), Some(77)));
    assert_eq!((rows.clone().min(), rows.max()), (Some(33), Some(44)));
}

#[test]
fn shared_edge_is_neither_doubled_nor_missed() {
    // A square with corners on pixel centres (4.5, 4.5) and (12.5, 12.5), split along
    // its diagonal, which runs through the centres (k + 0.5, k + 0.5).
    let (a, b, c, d) = (
        vec2(4.5, 4.5),
        vec2(12.5, 4.5),
        vec2(12.5, 12.5),
        vec2(4.5, 12.5),
    );
    let fill = |tris: &[[Vec2; 3]]| {
        let (mut cov, mut by_triangles) = (Coverage::default(), Coverage::default());
        cov.shape(16, 16);
        by_triangles.shape(16, 16);
        for t in tris {
            cov.fill_convex(t);
            by_triangles.fill_triangle(*t);
        }
        let mut check = cov.clone();
        assert_eq!(drained(&mut check), drained(&mut by_triangles));
        let mut pixels = Vec::new();
        for y in 0..16 {
            for x in 0..16 {
                if cov.get(x, y) {
                    pixels.push((x, y));
                }
            }
        }
        cov.drain(|_, _| {});
        pixels
    };
    for (upper, lower) in [([a, b, c], [a, c, d]), ([c, b, a], [d, c, a])] {
        let both = fill(&[upper, lower]);
        // Centres on the left and top edges are in, on the right and bottom out.
        assert_eq!(both, block(4..12, 4..12));
        let (u, l) = (fill(&[upper]), fill(&[lower]));
        assert_eq!(u.len() + l.len(), 64, "each diagonal centre counted once");
        assert!(u.iter().all(|p| !l.contains(p)));
        // The diagonal is the upper-right triangle's left edge and the lower-left one's
        // right edge: its centres belong to the upper-right one.
        assert!(u.contains(&(4, 4)) && u.contains(&(11, 11)) && !l.contains(&(7, 7)));
    }
}

#[test]
fn centres_exactly_on_a_sloped_edge_are_decided_exactly() {
    // The diagonal from (0.5, 0.5) to (58.5, 22.5) has the slope 29/11, which no binary
    // fraction holds, and passes exactly through the centre (29.5, 11.5) of pixel
    // (29, 11); in f32, 0.5 + 11 * (58 / 22) is 29.500002.
    let (a, b) = (vec2(0.5, 0.5), vec2(58.5, 22.5));
    let fill = |poly: &[Vec2]| {
        let (mut cov, mut by_triangle) = (Coverage::default(), Coverage::default());
        cov.shape(64, 24);
        by_triangle.shape(64, 24);
        cov.fill_convex(poly);
        by_triangle.fill_triangle([poly[0], poly[1], poly[2]]);
        let mut check = cov.clone();
        assert_eq!(drained(&mut check), drained(&mut by_triangle));
        let mut pixels = Vec::new();
        for y in 0..24 {
            pixels.extend((0..64).filter(|&x| cov.get(x, y)).map(|x| (x, y)));
        }
        pixels
    };
    // Below the diagonal it is the right edge (centre out), above it the left (centre in).
    let below = fill(&[a, b, vec2(0.5, 22.5)]);
    let above = fill(&[a, vec2(58.5, 0.5), b]);
    assert!(!below.contains(&(29, 11)) && below.contains(&(28, 11)));
    assert!(above.contains(&(29, 11)) && !above.contains(&(28, 11)));
    assert!(below.iter().all(|p| !above.contains(p)));
    // Together they cover the rectangle's centres once each: 58 columns by 22 rows.
    assert_eq!(below.len() + above.len(), 58 * 22);
}

/// The covered words of `cov`, in order, and the coverage cleared.
fn drained(cov: &mut Coverage) -> Vec<(usize, u64)> {
    let mut words = Vec::new();
    cov.drain(|w, bits| words.push((w, bits)));
    words.sort_unstable();
    words
}

/// `t` snapped to the nearest 1/256 of a pixel, as projected vertices are.
fn snapped(t: f32) -> f32 {
    (t * 256.0).round() / 256.0
}

/// The triangle fill covers exactly what the polygon fill covers, over random triangles
/// of every kind that decides pixels differently: tiny ones near centres, vertices and
/// edges on centres (ties), horizontal and vertical edges, slivers and near-collinear
/// ones, triangles larger than the image, and triangles beyond its exact range (which
/// it hands to the polygon fill). `SHAPEGEN_PROPERTY_SCALE` multiplies the cases.
#[test]
fn the_triangle_fill_covers_what_the_polygon_fill_covers() {
    let (width, height) = (150, 70);
    let (mut fast, mut slow) = (Coverage::default(), Coverage::default());
    fast.shape(width, height);
    slow.shape(width, height);
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let scale: usize = std::env::var("SHAPEGEN_PROPERTY_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let cases = scale
        * if cfg!(debug_assertions) {
            40_000
        } else {
            400_000
        };
    let mut covering = 0;
    for case in 0..cases {
        let centre = vec2(
            rng.random_range(-5.0..width as f32 + 5.0),
            rng.random_range(-5.0..height as f32 + 5.0),
        );
        let spread = [3.0f32, 40.0, 400.0, 3000.0, 12.0, 12.0, 12.0][case % 7];
        let mut tri = [(); 3].map(|_| {
            vec2(
                snapped(centre.x + rng.random_range(-spread..spread)),
                snapped(centre.y + rng.random_range(-spread..spread)),
            )
        });
        match case % 7 {
            // Vertices on pixel centres or half-way between, or one step off them.
            4 => {
                for p in &mut tri {
                    let step = rng.random_range(-1..=1) as f32 / 256.0;
                    *p = (*p * 2.0).round() / 2.0 + Vec2::splat(step);
                    if rng.random::<bool>() {
                        *p += vec2(0.5, 0.0);
                    }
                }
            }
            // A horizontal or vertical edge.
            5 => {
                if rng.random::<bool>() {
                    tri[1].y = tri[0].y;
                } else {
                    tri[1].x = tri[0].x;
                }
            }
            // Near-collinear: the third vertex on or a few steps off the line of the
            // other two.
            6 => {
                let t = rng.random_range(-1.0f32..2.0);
                let on = tri[0] + (tri[1] - tri[0]) * t;
                let off = rng.random_range(-3..=3) as f32 / 256.0;
                tri[2] = vec2(snapped(on.x) + off, snapped(on.y));
            }
            _ => {}
        }
        // Each triangle fills over what the last three filled, so that boxes already
        // covered are met too.
        if case % 4 == 0 {
            drained(&mut fast);
            drained(&mut slow);
        }
        let before = drained(&mut slow.clone());
        fast.fill_triangle(tri);
        slow.fill_convex(&tri);
        let (f, s) = (drained(&mut fast.clone()), drained(&mut slow.clone()));
        assert_eq!(f, s, "case {case}: {tri:?}");
        covering += usize::from(s != before);
    }
    // Most cases add pixels, so the comparison is not of unchanged coverages.
    assert!(covering > cases / 2, "{covering} of {cases} add a pixel");
}

#[test]
fn projected_vertices_snap_to_a_256th_of_a_pixel() {
    use super::raster::to_pixels;
    // x = (0.25 + 1) / 2 * 10 = 6.25 exactly; y lands between two steps and snaps to
    // the nearer.
    let p = to_pixels(
        Vec4::new(0.25, 1.0 - 2.0 * 3.0013 / 6.0, 0.0, 1.0),
        10.0,
        6.0,
    );
    assert_eq!(p.x, 6.25);
    assert_eq!(p.y * 256.0, (3.0013f32 * 256.0).round());
}

#[test]
fn horizontal_edges_follow_the_top_left_rule() {
    let mut cov = Coverage::default();
    cov.shape(8, 8);
    // Top edge y = 2.5 (centres of row 2) in, bottom edge y = 5.5 (row 5) out.
    cov.fill_convex(&[vec2(1.0, 2.5), vec2(7.0, 2.5), vec2(4.0, 5.5)]);
    assert!(cov.get(4, 2) && !cov.get(4, 5) && cov.get(4, 4));
    cov.drain(|_, _| {});
    cov.fill_convex(&[vec2(4.0, 2.5), vec2(7.0, 5.5), vec2(1.0, 5.5)]);
    assert!(!cov.get(4, 2) && !cov.get(4, 5) && cov.get(4, 3));
    let mut words = 0;
    cov.drain(|_, bits| words += bits.count_ones());
    // Row 3 spans x in [3, 5] (centres 3.5, 4.5), row 4 x in [2, 6] (2.5 to 5.5).
    assert_eq!(words, 2 + 4);
}

#[test]
fn near_plane_clips_before_the_divide() {
    let mut out = [Vec4::ZERO; 5];
    // One vertex behind the near plane (z < -w): the quad left has two new vertices
    // on the plane z = -w.
    let tri = [
        Vec4::new(0.0, 0.0, 0.0, 1.0),
        Vec4::new(1.0, 0.0, 0.0, 1.0),
        Vec4::new(0.0, 1.0, -3.0, 1.0),
    ];
    let n = clip_triangle(tri, &mut out);
    assert_eq!(n, 4);
    for v in &out[..n] {
        assert!(v.z + v.w >= -1e-6);
    }
    // The edges to the clipped vertex cross the plane a third and two thirds along.
    for on_plane in [
        Vec4::new(2.0 / 3.0, 1.0 / 3.0, -1.0, 1.0),
        Vec4::new(0.0, 1.0 / 3.0, -1.0, 1.0),
    ] {
        assert!(
            out[..n].iter().any(|v| v.abs_diff_eq(on_plane, 1e-6)),
            "{:?}",
            &out[..n]
        );
    }
    assert_eq!(
        clip_triangle(tri.map(|v| v - Vec4::new(0.0, 0.0, 5.0, 0.0)), &mut out),
        0
    );

    // A floor 1 below the eye, reaching from behind the camera to 105 ahead, seen
    // looking along +z: it covers the lower half of the image and nothing above the
    // horizon (without clipping, its vertices behind the eye would flip upwards).
    let camera = Camera::Orbit(orbit(-FRAC_PI_2, 0.0, 5.0, 60.0, 0.1, 1000.0));
    let target = ImageTarget::new("t".into(), &white(80, 60), camera, MASK).unwrap();
    let scorer = cube_scorer(target, SMOOTH);
    let floor = [cube(vec3(200.0, 0.01, 110.0), vec3(0.0, -1.0, 45.0))];
    // The far edge projects to ndc y = -s2 / 105: pixel row 30.3, so rows 30 to 59.
    assert_eq!(covered(&scorer, &floor), block(0..80, 30..60));
}

#[test]
fn mask_and_weight_map_fitness_from_hand_counts() {
    // 4 x 2 pixels; the identity camera maps x in [-1, 0] to columns 0 and 1.
    let levels = [[0u8, 100, 200, 255], [50, 128, 0, 0]];
    let image = GrayImage::from_fn(4, 2, |x, y| Luma([levels[y as usize][x as usize]]));
    let image = DynamicImage::ImageLuma8(image);
    let model = [cube(vec3(1.0, 2.0, 1.0), vec3(-0.5, 0.0, 0.0))];

    // The original's mask: only level 0 (red 0) is a target pixel; of the covered
    // levels 0, 100, 50 and 128, one is on target and three off.
    let original =
        ImageTarget::new("o".into(), &image, IDENTITY, Weighting::mask(2.0, -1.0)).unwrap();
    assert_eq!(original.target_pixels(), 3);
    let weighted = cube_scorer(original, WEIGHTED);
    let t = weighted.count(&model, &mut weighted.scratch()).targets()[0];
    assert_eq!((t.covered, t.on_target, t.off_target), (4, 1, 3));

    // A threshold mask: covered levels 0, 100, 50 (target) and 128 (not).
    let mask = ImageTarget::new(
        "m".into(),
        &image,
        IDENTITY,
        Weighting::mask_by(MaskRule::DarkerThan(128), 2.0, -1.0),
    )
    .unwrap();
    assert_eq!(mask.target_pixels(), 5);
    let weighted = cube_scorer(mask.clone(), WEIGHTED);
    let counts = weighted.count(&model, &mut weighted.scratch());
    let t = counts.targets()[0];
    assert_eq!(
        (t.covered, t.on_target, t.off_target, t.level_sum),
        (4, 3, 1, 255)
    );
    assert_eq!(weighted.fitness(&counts), 3.0 * 2.0 - 1.0);
    let smooth = cube_scorer(
        mask,
        Form::Smooth {
            good: 2.0,
            bad: 3.0,
        },
    );
    let f = smooth.fitness(&smooth.count(&model, &mut smooth.scratch()));
    let expected = 2.0 * smoothstep(0.0, 5.0, 3.0) - 3.0 * smoothstep(0.0, 5.0, 1.0);
    assert!((f - expected).abs() < 1e-12);

    // Weight map 1 - 2 g / 255: covered weights 1, 1 - 200/255, 1 - 100/255, 1 - 256/255.
    let map = ImageTarget::new("w".into(), &image, IDENTITY, MAP).unwrap();
    assert_eq!(map.target_pixels(), 5);
    let weighted = cube_scorer(map, WEIGHTED);
    let counts = weighted.count(&model, &mut weighted.scratch());
    let t = counts.targets()[0];
    assert_eq!((t.covered, t.on_target, t.level_sum), (4, 3, 278));
    let expected = 4.0 - 2.0 * 278.0 / 255.0;
    assert!((weighted.fitness(&counts) - expected).abs() < 1e-12);
}

#[test]
fn a_shaped_mask_costs_off_target_pixels_by_their_distance() {
    // 10 x 1 pixels, columns 0 and 1 the target; the cube covers columns 0 to 4, the
    // off-target ones 1, 2 and 3 pixels from the target.
    let image = GrayImage::from_fn(10, 1, |x, _| Luma([if x < 2 { 0 } else { 255 }]));
    let image = DynamicImage::ImageLuma8(image);
    let model = [cube(vec3(1.0, 2.0, 1.0), vec3(-0.5, 0.0, 0.0))];
    let mask = ImageTarget::new("m".into(), &image, IDENTITY, MASK).unwrap();
    let plain = cube_scorer(mask.clone(), SMOOTH);
    let counts = plain.count(&model, &mut plain.scratch());
    assert_eq!(
        plain.targets()[0].off_target_cost(&counts.targets()[0]),
        3.0
    );

    // Zero weight at level ceil(255 / 2) = 128; shares 1/4, 2/4, 3/4 of the 127 levels
    // above it, rounded up: 160, 192, 224; 4 pixels and more away, 255.
    let shaped = mask.shaped(4.0).unwrap();
    assert!(shaped.is_shaped());
    let levels: Vec<u8> = (0..10).map(|x| shaped.level(x, 0)).collect();
    assert_eq!(levels, [0, 0, 160, 192, 224, 255, 255, 255, 255, 255]);
    assert_eq!(shaped.target_pixels(), 2);

    let weighted = cube_scorer(shaped.clone(), WEIGHTED);
    let counts = weighted.count(&model, &mut weighted.scratch());
    let t = counts.targets()[0];
    assert_eq!((t.covered, t.on_target, t.off_target), (5, 2, 3));
    let expected = 5.0 - 2.0 * (160.0 + 192.0 + 224.0) / 255.0;
    assert!((weighted.fitness(&counts) - expected).abs() < 1e-12);

    let smooth = cube_scorer(shaped, SMOOTH);
    let counts = smooth.count(&model, &mut smooth.scratch());
    let cost = (32.0 + 64.0 + 96.0) / 127.0;
    assert!((smooth.targets()[0].off_target_cost(&counts.targets()[0]) - cost).abs() < 1e-12);
    let expected = smoothstep(0.0, 2.0, 2.0) - smoothstep(0.0, 2.0, cost);
    assert!((smooth.fitness(&counts) - expected).abs() < 1e-12);
}

#[test]
fn shaping_is_refused_where_it_has_no_meaning() {
    let image = DynamicImage::ImageLuma8(GrayImage::from_fn(4, 1, |x, _| Luma([x as u8 * 80])));
    let mask = ImageTarget::new("m".into(), &image, IDENTITY, MASK).unwrap();
    let reason = |target: ImageTarget, radius: f32| target.shaped(radius).unwrap_err().to_string();
    assert_eq!(
        reason(mask.clone(), 0.0),
        "target `m`: distance shaping radius is 0; it must be a positive number of pixels"
    );
    assert!(reason(mask.clone(), f32::NAN).contains("positive number of pixels"));
    let map = ImageTarget::new("w".into(), &image, IDENTITY, MAP).unwrap();
    assert!(reason(map, 4.0).contains("needs a mask"));
    for (on, off) in [(1.0, 0.0), (1.0, 0.5), (-1.0, -2.0), (1.0, -0.001)] {
        let mask =
            ImageTarget::new("m".into(), &image, IDENTITY, Weighting::mask(on, off)).unwrap();
        assert!(
            reason(mask, 4.0).contains("needs on > 0 > off"),
            "on {on}, off {off}"
        );
    }
}

#[test]
fn several_targets_add_up() {
    let a = ImageTarget::new("a".into(), &white(4, 2), IDENTITY, MASK).unwrap();
    let b = ImageTarget::new(
        "b".into(),
        &white(8, 8),
        IDENTITY,
        Weighting::weight_map(1.0, -0.5),
    )
    .unwrap();
    let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
    let scorer = SilhouetteScorer::new(vec![a, b], &meshes, WEIGHTED).unwrap();
    let model = [cube(Vec3::ONE, Vec3::ZERO)];
    let counts = scorer.count(&model, &mut scorer.scratch());
    let covered: Vec<u32> = counts.targets().iter().map(|t| t.covered).collect();
    // The cube spans ndc [-0.5, 0.5]: columns 1..3 of 4 x rows 0.5..1.5 of 2; 2..6 of 8.
    assert_eq!(covered, [2, 16]);
    assert_eq!(scorer.fitness(&counts), -2.0 - 0.5 * 16.0);
}

#[test]
fn box_fast_path_agrees_with_triangles() {
    let camera = Camera::Orbit(OrbitCamera {
        lookat: vec3(0.0, 1.0, 0.0),
        ..orbit(0.4, 0.3, 12.0, 60.0, 0.1, 100.0)
    });
    let target = ImageTarget::new("t".into(), &white(160, 120), camera, MASK).unwrap();
    let fast = cube_scorer(target, SMOOTH);
    assert!(fast.meshes[0].hull.is_some(), "the cube is convex");
    let mut slow = fast.clone();
    slow.meshes[0].hull = None;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut s1, mut s2) = (fast.scratch(), slow.scratch());
    for _ in 0..200 {
        let model: Vec<Instance> = (0..rng.random_range(1..20))
            .map(|_| {
                let scale = Vec3::from(rng.random::<[f32; 3]>()) * 3.0 + 0.05;
                let at = (Vec3::from(rng.random::<[f32; 3]>()) - 0.5) * 10.0;
                let rotation = glam::Quat::from_euler(
                    glam::EulerRot::YXZ,
                    rng.random::<f32>() * 6.3,
                    rng.random::<f32>() * 6.3,
                    rng.random::<f32>() * 6.3,
                );
                Instance {
                    transform: Affine3A::from_scale_rotation_translation(scale, rotation, at),
                    mesh: CUBE,
                }
            })
            .collect();
        let (a, b) = (fast.count(&model, &mut s1), slow.count(&model, &mut s2));
        let (a, b) = (a.targets()[0].covered, b.targets()[0].covered);
        // Hull edges are the silhouette triangles' edges; only centres within rounding
        // of an edge through a hidden collinear corner may differ.
        assert!(a.abs_diff(b) <= model.len() as u32, "{a} vs {b}");
    }
}

#[test]
fn convex_hull_of_a_square_with_inner_points() {
    let mut points = [
        vec2(0.0, 0.0),
        vec2(2.0, 0.0),
        vec2(1.0, 1.0),
        vec2(2.0, 2.0),
        vec2(0.0, 2.0),
        vec2(0.5, 1.5),
    ];
    let mut hull = [Vec2::ZERO; MAX_POLYGON + 1];
    let n = convex_hull(&mut points, &mut hull);
    assert_eq!(n, 4);
    for corner in [
        vec2(0.0, 0.0),
        vec2(2.0, 0.0),
        vec2(2.0, 2.0),
        vec2(0.0, 2.0),
    ] {
        assert!(hull[..n].contains(&corner));
    }
}

#[test]
fn camera_errors_name_the_field_and_the_valid_range() {
    let good = orbit(0.0, 0.0, 5.0, 60.0, 0.1, 100.0);
    assert_eq!(Camera::Orbit(good).validate(), Ok(()));
    let cases = [
        (
            OrbitCamera {
                radius: 0.0,
                ..good
            },
            "camera `radius` is 0; it must be greater than 0",
        ),
        (
            OrbitCamera {
                fov_degrees: 180.0,
                ..good
            },
            "camera `fov` is 180 degrees; it must lie strictly between 0 and 180",
        ),
        (
            OrbitCamera {
                near: 100.0,
                ..good
            },
            "camera `near` is 100 and `far` is 100; they must satisfy 0 < near < far",
        ),
        (
            OrbitCamera {
                phi: f32::NAN,
                ..good
            },
            "camera `phi` is NaN; it must be a finite number",
        ),
    ];
    for (camera, message) in cases {
        assert_eq!(
            Camera::Orbit(camera).validate().unwrap_err().to_string(),
            message
        );
    }
    let bad = Camera::Matrices {
        view: Mat4::IDENTITY,
        projection: Mat4::from_diagonal(Vec4::splat(f32::INFINITY)),
    };
    assert_eq!(
        bad.validate().unwrap_err().to_string(),
        "camera `projection` matrix has a non-finite entry"
    );
    let err = ImageTarget::new(
        "sky".into(),
        &white(4, 4),
        Camera::Orbit(OrbitCamera {
            radius: -1.0,
            ..good
        }),
        MASK,
    )
    .unwrap_err();
    assert_eq!(
        crate::error::error_chain(&err),
        "target `sky`: camera `radius` is -1; it must be greater than 0"
    );
}

#[test]
fn target_errors_name_the_image_and_the_limit() {
    let err = ImageTarget::new("e".into(), &white(0, 3), IDENTITY, MASK).unwrap_err();
    assert_eq!(
        err.to_string(),
        "target `e`: the image is 0 x 3; it must have at least one pixel"
    );
    let err = ImageTarget::new(
        "big".into(),
        &white(4097, 4096),
        IDENTITY,
        Weighting::weight_map(1.0, 0.0),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "target `big`: the image is 4097 x 4096; at most 16777216 pixels are supported \
         (for example 4096 x 4096)"
    );
    let err = ImageTarget::new(
        "w".into(),
        &white(2, 2),
        IDENTITY,
        Weighting::mask(f32::NAN, 0.0),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "target `w`: weight `on` is NaN; it must be a finite number"
    );
}

#[test]
fn scorer_errors_name_the_limit() {
    let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
    let t = ImageTarget::new("t".into(), &white(4, 4), IDENTITY, MASK).unwrap();
    let err = SilhouetteScorer::new(vec![t.clone(); 9], &meshes, SMOOTH).unwrap_err();
    assert_eq!(
        err.to_string(),
        "9 target images given; a silhouette scorer takes at most 8"
    );
    assert!(SilhouetteScorer::new(vec![t.clone(); 8], &meshes, SMOOTH).is_ok());
    assert_eq!(
        SilhouetteScorer::new(Vec::new(), &meshes, SMOOTH).unwrap_err(),
        SilhouetteError::NoTargets
    );
    let err = SilhouetteScorer::new(vec![t.clone()], &meshes, Form::Weighted { overlap: 1.0 })
        .unwrap_err();
    assert!(err.to_string().contains("`overlap` is 1"), "{err}");
    let scorer = SilhouetteScorer::new(vec![t], &meshes, SMOOTH).unwrap();
    let err = scorer.coverage_mask(0, &[], &mut [false; 15]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "a coverage mask of 15 pixels given for target `t`, which has 16"
    );
    let err = scorer.coverage_mask(2, &[], &mut [false; 16]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "target 2 asked for; the scorer has 1 targets (0..1)"
    );
}

#[test]
fn the_tree_meshes_take_the_hull_path_and_a_concave_mesh_does_not() {
    // Copies of the tree generator's meshes, so that the crate's tests stay inside it.
    let trunk = crate::geometry::Mesh::from_obj_str("trunk", include_str!("testdata/trunk.obj"));
    let leaf = crate::geometry::Mesh::from_obj_str("leaf", include_str!("testdata/leaf.obj"));
    let mut library = MeshLibrary::new();
    library.register("trunk", trunk.unwrap()).unwrap();
    library.register("leaf", leaf.unwrap()).unwrap();
    // A cube with one corner pushed in is concave.
    let mut dented = crate::geometry::Mesh::unit_cube();
    for p in &mut dented.positions {
        if *p == Vec3::splat(0.5) {
            *p = Vec3::splat(0.1);
        }
    }
    library.register("dented", dented).unwrap();
    let bound = library
        .bind_names("T", &["cube", "trunk", "leaf", "dented"])
        .unwrap();
    let prepared = meshes::prepare(&bound);
    let hulls: Vec<bool> = prepared.iter().map(|m| m.hull.is_some()).collect();
    assert_eq!(hulls, [true, true, true, false]);
}

#[test]
fn masks_by_alpha_and_by_distance_from_a_background_colour() {
    use image::{Rgba, RgbaImage};
    // A photo-like 4 x 1 strip: white backdrop, near-white noise, a red object pixel
    // (transparent), and a grey object pixel (opaque).
    let pixels = [
        Rgba([255, 255, 255, 0]),
        Rgba([250, 245, 255, 0]),
        Rgba([200, 30, 30, 100]),
        Rgba([90, 90, 90, 255]),
    ];
    let image = DynamicImage::ImageRgba8(RgbaImage::from_fn(4, 1, |x, _| pixels[x as usize]));
    let target = |rule| {
        ImageTarget::new(
            "t".into(),
            &image,
            IDENTITY,
            Weighting::mask_by(rule, 1.0, -1.0),
        )
    };
    let pixels_of = |t: &ImageTarget| (0..4).filter(|&x| t.weight(x, 0) > 0.0).collect::<Vec<_>>();

    let opaque = target(MaskRule::OpaqueFrom(128)).unwrap();
    assert_eq!(pixels_of(&opaque), [3]);
    let visible = target(MaskRule::OpaqueFrom(1)).unwrap();
    assert_eq!(pixels_of(&visible), [2, 3]);

    // The noise pixel is sqrt(25 + 100) ~ 11.2 from white: within 12, not within 11.
    let backdrop = |tolerance| MaskRule::FarFrom {
        background: [255, 255, 255],
        tolerance,
    };
    assert_eq!(pixels_of(&target(backdrop(12)).unwrap()), [2, 3]);
    assert_eq!(pixels_of(&target(backdrop(11)).unwrap()), [1, 2, 3]);
}

/// A sphere-like closed mesh of `rings` x `sectors` quads (two triangles each) and two
/// poles, wound consistently; positions are unit-sphere points (their projection is
/// chosen by the caller).
fn closed_mesh(rings: u32, sectors: u32) -> crate::geometry::Mesh {
    let mut positions = vec![Vec3::Y, -Vec3::Y];
    for r in 0..rings {
        let lat = std::f32::consts::PI * (r as f32 + 1.0) / (rings as f32 + 1.0);
        for s in 0..sectors {
            let lon = std::f32::consts::TAU * s as f32 / sectors as f32;
            positions.push(vec3(
                lat.sin() * lon.cos(),
                lat.cos(),
                lat.sin() * lon.sin(),
            ));
        }
    }
    let at = |r: u32, s: u32| 2 + r * sectors + s % sectors;
    let mut indices = Vec::new();
    for s in 0..sectors {
        indices.extend([0, at(0, s + 1), at(0, s)]);
        indices.extend([1, at(rings - 1, s), at(rings - 1, s + 1)]);
        for r in 0..rings - 1 {
            let (a, b, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1));
            indices.extend([a, b, d, a, d, c]);
        }
    }
    crate::geometry::Mesh {
        normals: positions.clone(),
        positions,
        indices,
    }
}

/// A closed mesh of random resolution, for case `case` of the mesh fill test: whole,
/// with holes (some triangles taken out) or wound inconsistently (some turned).
fn damaged_mesh(case: usize, rng: &mut ChaCha8Rng) -> crate::geometry::Mesh {
    let mut mesh = closed_mesh(rng.random_range(1..6), rng.random_range(3..9));
    match case % 4 {
        // Holes: some triangles taken out.
        1 => {
            let n = mesh.indices.len() / 3;
            for _ in 0..rng.random_range(1..4) {
                let t = rng.random_range(0..mesh.indices.len() / 3);
                mesh.indices.drain(3 * t..3 * t + 3);
            }
            assert!(mesh.indices.len() / 3 < n);
        }
        // Inconsistent winding: some triangles turned.
        2 => {
            for _ in 0..rng.random_range(1..3) {
                let t = rng.random_range(0..mesh.indices.len() / 3);
                mesh.indices.swap(3 * t, 3 * t + 1);
            }
        }
        _ => {}
    }
    mesh
}

/// Image positions, snapped to the subpixel grid, for a mesh's `positions` placed at
/// random in an image of `width` x `height` pixels (and up to 10 beyond): a sphere's projection
/// under a random rotation, or points anywhere, on a coarse lattice of centres and
/// edges, or all but one on a line.
fn placed_points(
    positions: &[Vec3],
    (width, height): (u32, u32),
    rng: &mut ChaCha8Rng,
) -> Vec<Vec2> {
    use super::raster::SUBPIXEL;
    let centre = vec2(
        rng.random_range(-10.0..width as f32 + 10.0),
        rng.random_range(-10.0..height as f32 + 10.0),
    );
    let size = [2.0f32, 8.0, 30.0, 120.0][rng.random_range(0..4)];
    let rotation = glam::Quat::from_euler(
        glam::EulerRot::XYZ,
        rng.random_range(0.0..6.3),
        rng.random_range(0.0..6.3),
        rng.random_range(0.0..6.3),
    );
    let style = rng.random_range(0..4);
    positions
        .iter()
        .map(|&p| {
            let q = match style {
                0 => (rotation * p).truncate() * size,
                1 => vec2(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)) * size,
                2 => ((rotation * p).truncate() * size * 2.0).round() / 2.0,
                _ => vec2(
                    p.y * size,
                    p.y * size * 0.37 + rng.random_range(-1..=1) as f32 / 256.0,
                ),
            };
            ((centre + q) * SUBPIXEL).round() / SUBPIXEL
        })
        .collect()
}

/// Filling a whole mesh with its negative triangles left out where they cannot add a
/// pixel covers exactly what filling every triangle covers: on closed meshes, meshes
/// with holes (triangles taken out), meshes wound inconsistently (triangles turned),
/// with random positions in the image, tiny and large, on pixel centres and near
/// collinear, so that ties, slivers and triangles whose `f32` area disagrees with the
/// exact one all occur. `SHAPEGEN_PROPERTY_SCALE` multiplies the cases.
#[test]
fn filling_a_mesh_covers_what_filling_its_triangles_covers() {
    use super::mesh_fill::{MeshScratch, ProjectedMesh};
    use super::meshes::RasterMesh;
    use super::raster::to_fixed;
    let (width, height) = (96, 64);
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let scale: usize = std::env::var("SHAPEGEN_PROPERTY_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let cases = scale * if cfg!(debug_assertions) { 400 } else { 4000 };
    let (mut whole, mut each) = (Coverage::default(), Coverage::default());
    whole.shape(width, height);
    each.shape(width, height);
    let mut scratch = MeshScratch::default();
    let (mut left_out, mut with_holes, mut pixels) = (0, 0, 0);
    for case in 0..cases {
        let mesh = damaged_mesh(case, &mut rng);
        let raster = RasterMesh::new(&mesh);
        with_holes += usize::from(!raster.boundary.is_empty());
        let points = placed_points(&raster.positions, (width, height), &mut rng);
        let fixed: Vec<[i32; 2]> = points.iter().map(|&p| to_fixed(p)).collect();
        let projected = ProjectedMesh {
            mesh: &raster,
            points: &points,
            fixed: &fixed,
        };
        whole.fill_mesh(&projected, &mut scratch);
        for t in &raster.triangles {
            each.fill_triangle(t.map(|i| points[i as usize]));
        }
        let (w, e) = (drained(&mut whole), drained(&mut each));
        assert_eq!(w, e, "case {case}");
        left_out += scratch.left_out();
        pixels += e
            .iter()
            .map(|(_, bits)| bits.count_ones() as usize)
            .sum::<usize>();
    }
    // The cases cover pixels, leave triangles out, and have holes.
    assert!(pixels > cases * 10, "{pixels} pixels in {cases} cases");
    assert!(
        left_out > cases,
        "{left_out} triangles left out in {cases} cases"
    );
    assert!(
        with_holes > cases / 4,
        "{with_holes} of {cases} meshes with holes"
    );
}

/// A closed mesh of two triangles, one the other turned over, whose positive triangle's
/// `f32` area disagrees with its exact one while the negative one's agrees: the
/// positive triangle covers nothing, so the mesh covers what the negative one covers,
/// which the mesh fill must then fill although the mesh is closed.
#[test]
fn a_mesh_whose_positive_triangle_is_dropped_covers_what_its_negative_one_covers() {
    use super::mesh_fill::{MeshScratch, ProjectedMesh};
    use super::meshes::RasterMesh;
    use super::raster::{SUBPIXEL, exact_area, f32_agrees, signed_area, to_fixed};
    let (width, height) = (96, 64);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    // Slivers through the image, their ends `a` and `b` some 1,900 pixels either side of
    // a pixel centre `c`, the third corner, one lattice step off their line (twice the
    // area 1/65536 px^2): there the `f32` areas, from coordinates near 2,000 pixels,
    // err far more than the area. `c`'s corner is nearly flat, so the triangle covers
    // `c` in about half the cases.
    let found = (0..100_000).find_map(|_| {
        let c = [
            256 * rng.random_range(0..width as i64) + 128,
            256 * rng.random_range(0..height as i64) + 128,
        ];
        let d = [
            rng.random_range(300_000..480_000i64),
            rng.random_range(-480_000..480_000i64),
        ];
        // e with cross(e, d) = e.x d.y - e.y d.x = 1, near d: (u, v) + k d.
        let (g, u, v) = extended_gcd(d[1], -d[0]);
        if g != 1 {
            return None;
        }
        let k = 1 - (u * d[0] + v * d[1]) / (d[0] * d[0] + d[1] * d[1]);
        let e = [u + k * d[0], v + k * d[1]];
        let (a, b) = ([c[0] - d[0], c[1] - d[1]], [c[0] + e[0], c[1] + e[1]]);
        let px = |p: [i64; 2]| vec2(p[0] as f32, p[1] as f32) / SUBPIXEL;
        let (a, b, c) = (px(a), px(b), px(c));
        let exact = exact_area(&[a, b, c].map(to_fixed));
        let (pos, neg) = if exact > 0 {
            ([a, b, c], [a, c, b])
        } else {
            ([a, c, b], [a, b, c])
        };
        let exact = exact.abs();
        let dropped = exact != 0
            && !f32_agrees(signed_area(&pos), exact)
            && f32_agrees(signed_area(&neg), -exact);
        let mut cov = Coverage::default();
        cov.shape(width, height);
        cov.fill_triangle(neg);
        let covered = !drained(&mut cov).is_empty();
        (dropped && covered).then_some(pos)
    });
    let [a, b, c] = found.expect("a sliver whose positive triangle alone is dropped");
    let mesh = crate::geometry::Mesh {
        positions: vec![Vec3::X, Vec3::Y, Vec3::Z],
        normals: vec![Vec3::Z; 3],
        indices: vec![0, 1, 2, 0, 2, 1],
    };
    let raster = RasterMesh::new(&mesh);
    assert!(
        raster.boundary.is_empty(),
        "the two triangles close each other"
    );
    let points = vec![a, b, c];
    let fixed: Vec<[i32; 2]> = points.iter().map(|&p| to_fixed(p)).collect();
    let (mut whole, mut each) = (Coverage::default(), Coverage::default());
    whole.shape(width, height);
    each.shape(width, height);
    whole.fill_mesh(
        &ProjectedMesh {
            mesh: &raster,
            points: &points,
            fixed: &fixed,
        },
        &mut MeshScratch::default(),
    );
    each.fill_triangle([a, b, c]);
    each.fill_triangle([a, c, b]);
    let expected = drained(&mut each);
    assert!(!expected.is_empty());
    assert_eq!(drained(&mut whole), expected);
}

/// `(g, u, v)` with `g = gcd(a, b) = a u + b v`.
fn extended_gcd(a: i64, b: i64) -> (i64, i64, i64) {
    if b == 0 {
        (a.abs(), a.signum(), 0)
    } else {
        let (g, u, v) = extended_gcd(b, a.rem_euclid(b));
        (g, v, u - a.div_euclid(b) * v)
    }
}

/// A state keeps what each of its instances covers where replaying it is cheaper than
/// rasterizing the instance again (a small ball of 194 hull points, not a large cube of
/// 8), shared with the states made from it: the counts stay those of the model counted
/// from nothing, repeated instances and instances without a kept footprint included.
#[test]
fn a_state_keeps_and_shares_the_footprints_worth_keeping() {
    use crate::score::retained::RetainedScorer;

    let camera = Camera::Orbit(orbit(-FRAC_PI_2, 0.0, 6.0, 60.0, 0.1, 100.0));
    let target = ImageTarget::new("white".into(), &white(64, 48), camera, MASK).unwrap();
    let mut library = MeshLibrary::new();
    library.register("ball", closed_mesh(12, 16)).unwrap();
    let meshes = library.bind_names("T", &["cube", "ball"]).unwrap();
    let form = Form::Smooth {
        good: 1.0,
        bad: 1.0,
    };
    let scorer = SilhouetteScorer::new(vec![target], &meshes, form).unwrap();
    let ball = |x: f32, y: f32| Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::splat(0.2),
            glam::Quat::IDENTITY,
            vec3(x, y, 0.0),
        ),
        mesh: crate::geometry::MeshId(CUBE.0 + 1),
    };
    let (a, b, c) = (ball(-1.0, 0.0), ball(0.0, 0.1), ball(0.8, 0.3));
    let big = cube(Vec3::splat(1.5), vec3(0.5, -0.5, 0.0));
    let blocks = |state: &WithFootprints<SilhouetteState>| {
        let mut seen = Vec::new();
        scorer.visit_blocks(state, &mut |address, bytes| seen.push((address, bytes)));
        seen
    };
    let mut scratch = scorer.scratch();
    let parent = scorer
        .count_retained(&[a, b, big, b], &mut scratch)
        .unwrap();
    assert_eq!(
        scorer.state_counts(&parent),
        scorer.count(&[a, b, big, b], &mut scratch)
    );
    // The list, then one footprint per ball: the cube's is not kept.
    let before = blocks(&parent);
    assert_eq!(before.len(), 1 + 3);

    let mut child = parent.clone();
    scorer
        .update(&mut child, &[b, big], &[c], &mut scratch)
        .unwrap();
    assert_eq!(
        scorer.state_counts(&child),
        scorer.count(&[a, b, c], &mut scratch)
    );
    let after = blocks(&child);
    let shared = after[1..]
        .iter()
        .filter(|f| before[1..].contains(f))
        .count();
    assert_eq!(
        (after.len(), shared),
        (1 + 3, 2),
        "a and one b shared, c new"
    );

    scorer
        .update(&mut child, &[b, a], &[big], &mut scratch)
        .unwrap();
    assert_eq!(
        scorer.state_counts(&child),
        scorer.count(&[c, big], &mut scratch)
    );
    scorer
        .update(&mut child, &[big, c], &[], &mut scratch)
        .unwrap();
    assert_eq!(scorer.state_counts(&child), scorer.count(&[], &mut scratch));
    assert_eq!(blocks(&child).len(), 1);
    // The parent is as it was.
    assert_eq!(
        scorer.state_counts(&parent),
        scorer.count(&[a, b, big, b], &mut scratch)
    );
}
