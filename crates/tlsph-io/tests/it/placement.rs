//! Where bodies start: two bodies that start inside each other (too close, or one embedded in
//! the other on any lattice), a body that starts behind a rigid wall, bodies on both sides of a
//! symmetry plane, or a particle closer to a plane than a quarter spacing are refused by
//! `tlsph check` at their line, naming the bodies (and a particle).

use super::{error_of, line_of};
use tlsph_io::parse_scene;
use tlsph_solver::WallShape;

/// Two 2D blocks of spacing 1 mm side by side along x; `GAP` is the x of the second block's
/// left face, so its first column of particles is half a spacing further.
const TWO_BLOCKS: &str = r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.0e-6

[[material]]
name = "steel"
model = "linear-elastic"
density = 7850.0
youngs_modulus = 200.0e9
poisson_ratio = 0.3

[[body]]
name = "left"
material = "steel"
spacing = 1.0e-3
box = { min = [0.0, 0.0], max = [10.0e-3, 10.0e-3] }

[[body]]
name = "right"
material = "steel"
spacing = 1.0e-3
box = { min = [GAP, 0.0], max = [20.0e-3, 10.0e-3] }
velocity = [-10.0, 0.0]

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
"#;

#[test]
fn bodies_that_start_inside_each_other_are_refused_at_the_later_body() {
    // Touching faces (particle rows one spacing apart) and a gap are fine.
    for gap in ["10.0e-3", "10.5e-3"] {
        parse_scene(&TWO_BLOCKS.replace("GAP", gap), "blocks.toml").unwrap();
    }
    // Overlapping by 9.8 spacings: the right block's first column (x = 0.7 mm) sits 0.2 mm
    // from the left block's first (x = 0.5 mm).
    let text = TWO_BLOCKS.replace("GAP", "0.2e-3");
    let e = error_of(&text);
    assert_eq!(e.field, "body[right]", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "name = \"right\"")), "{e}");
    assert!(
        e.message.contains("inside body `left`")
            && e.message.contains("at [0.0007, 0.0005] is 2.000e-4"),
        "{e}"
    );
}

#[test]
fn a_body_embedded_in_another_on_an_offset_lattice_is_refused() {
    // The right block moved into the left one with its lattice offset by half a spacing: no
    // pair is closer than half a spacing (the rule above passes it), but every cell of the
    // right block's first column lies within the left block's cells (a first-user review
    // found such scenes accepted, starting with contact energy).
    for (right_box, at) in [
        // Half a spacing off along x: the nearest pair is exactly half a spacing apart.
        (
            "min = [5.5e-3, 0.0], max = [20.0e-3, 10.0e-3]",
            "at [0.006, 0.0005]",
        ),
        // Half off along x and y: 0.71 spacing apart.
        (
            "min = [5.5e-3, 0.5e-3], max = [20.0e-3, 9.5e-3]",
            "at [0.006, 0.001]",
        ),
    ] {
        let text = TWO_BLOCKS.replace("min = [GAP, 0.0], max = [20.0e-3, 10.0e-3]", right_box);
        let e = error_of(&text);
        assert_eq!(e.field, "body[right]", "{right_box}: {e}");
        assert_eq!(e.line, Some(line_of(&text, "name = \"right\"")), "{e}");
        assert!(
            e.message
                .contains("starts inside body `left`: the cell of its particle")
                && e.message.contains(at)
                && e.message
                    .contains("lies within the cells of `left`'s particles"),
            "{right_box}: {e}"
        );
    }
}

/// A scene of TWO_BLOCKS' simulation and material with the bodies `first` and `second`.
fn two_bodies(first: &str, second: &str) -> String {
    let header = &TWO_BLOCKS[..TWO_BLOCKS.find("[[body]]").expect("a body")];
    format!("{header}{first}\n\n{second}\n")
}

/// A coarse 2D plate (spacing 1 mm, 10 × 10 mm) and a fine disc (spacing 0.1 mm) of radius
/// 0.3 mm about `CENTRE`.
const PLATE: &str = r#"[[body]]
name = "plate"
material = "steel"
spacing = 1.0e-3
box = { min = [0.0, 0.0], max = [10.0e-3, 10.0e-3] }"#;

const DISC: &str = r#"[[body]]
name = "disc"
material = "steel"
spacing = 0.1e-3
disc = { centre = CENTRE, radius = 0.3e-3 }"#;

#[test]
fn a_fine_body_inside_a_coarse_one_is_refused_whichever_is_declared_first() {
    // The disc sits between four plate particles (0.42 mm from each, more than half of either
    // spacing): only the cells show that it is inside the plate.
    let disc = DISC.replace("CENTRE", "[5.0e-3, 5.0e-3]");
    let text = two_bodies(PLATE, &disc);
    let e = error_of(&text);
    assert_eq!(e.field, "body[disc]", "{e}");
    assert!(
        e.message
            .contains("starts inside body `plate`: the cell of its particle"),
        "{e}"
    );
    // Declared first, the disc is the earlier body: the plate is named, as lying around it.
    let text = two_bodies(&disc, PLATE);
    let e = error_of(&text);
    assert_eq!(e.field, "body[plate]", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "name = \"plate\"")), "{e}");
    assert!(
        e.message
            .contains("starts around body `disc`: the cell of `disc`'s particle")
            && e.message
                .contains("lies within the cells of `plate`'s particles"),
        "{e}"
    );
    // Resting on the plate (tangent to its top face) or beside it, the disc is accepted.
    for centre in ["[5.0e-3, 10.3e-3]", "[10.3e-3, 5.0e-3]"] {
        let text = two_bodies(PLATE, &DISC.replace("CENTRE", centre));
        parse_scene(&text, "plate.toml").unwrap();
    }
}

#[test]
fn a_body_that_starts_behind_a_wall_is_refused_at_the_wall() {
    let ok = TWO_BLOCKS.replace("GAP", "10.0e-3");
    // The floor at y = 0 touches both blocks' bottom faces; raised to y = 2 mm it has the
    // bottom two rows of the left block behind it (the lowest at 1.5 mm beyond the plane).
    let text = ok.replace("point = [0.0, 0.0]", "point = [0.0, 2.0e-3]");
    let e = error_of(&text);
    assert_eq!(e.field, "wall[floor].point", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "point = [0.0, 2.0e-3]")), "{e}");
    assert!(
        e.message.contains("body `left` starts behind the wall")
            && e.message.contains("is 1.500e-3 on the far side"),
        "{e}"
    );
}

#[test]
fn bodies_on_both_sides_of_a_symmetry_plane_are_refused_at_the_plane() {
    // The plane x = 10.25 mm between the blocks: each lies on one side, but a symmetry model
    // keeps every body on the modelled side (each would meet the other's mirror image).
    let text = TWO_BLOCKS.replace("GAP", "10.5e-3")
        + "\n[[symmetry_plane]]\naxis = \"x\"\nposition = 10.25e-3\n";
    let e = error_of(&text);
    assert_eq!(e.field, "symmetry_plane.position", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "position = 10.25e-3")), "{e}");
    assert!(
        e.message
            .contains("body `right` lies on the other side of this plane than body `left`"),
        "{e}"
    );
    // Both on the same side of x = 0 is a valid half model.
    parse_scene(
        &(TWO_BLOCKS.replace("GAP", "10.5e-3")
            + "\n[[symmetry_plane]]\naxis = \"x\"\nposition = -0.1e-3\n"),
        "blocks.toml",
    )
    .unwrap();
}

#[test]
fn a_second_plane_normal_to_the_same_axis_is_refused_at_its_axis() {
    // A plane declared twice made the run panic in the bond builder (a first-user review):
    // now `tlsph check` refuses it at the second plane's `axis`.
    let text = TWO_BLOCKS.replace("GAP", "10.5e-3")
        + "\n[[symmetry_plane]]\naxis = \"x\"\nposition = -0.1e-3\n\n[[symmetry_plane]]\naxis = \"x\" # again\nposition = -0.1e-3\n";
    let e = error_of(&text);
    assert_eq!(e.field, "symmetry_plane.axis", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "# again")), "{e}");
    assert!(e.message.contains("one symmetry plane per axis"), "{e}");
}

#[test]
fn a_particle_closer_to_a_plane_than_a_quarter_spacing_is_refused_at_the_plane() {
    // The left block's first column lies at x = 0.5 mm; a plane at x = 0.3 mm passes 0.2
    // spacing from it (its image would be 0.4 spacing away): refused, naming the particle.
    // At 0.25 mm (a quarter spacing) it is accepted, as is the usual plane on the face.
    let blocks = TWO_BLOCKS.replace("GAP", "10.5e-3");
    let plane = |x: &str| format!("{blocks}\n[[symmetry_plane]]\naxis = \"x\"\nposition = {x}\n");
    let text = plane("0.3e-3");
    let e = error_of(&text);
    assert_eq!(e.field, "symmetry_plane.position", "{e}");
    assert_eq!(e.line, Some(line_of(&text, "position = 0.3e-3")), "{e}");
    assert!(
        e.message
            .contains("body `left` has a particle at [0.0005, 0.0005], 2.000e-4 from this plane")
            && e.message.contains("less than a quarter of its spacing"),
        "{e}"
    );
    for x in ["0.25e-3", "0.0"] {
        parse_scene(&plane(x), "blocks.toml").unwrap();
    }
}

#[test]
fn a_finite_wall_is_read_and_only_its_footprint_must_be_clear() {
    // A punch: a segment of half-length 2 mm over the left block's top face, pressing down.
    let punch = "\n[[wall]]\nname = \"punch\"\npoint = [5.0e-3, 10.0e-3]\nnormal = [0.0, -1.0]\nradius = 2.0e-3\nvelocity = [0.0, -1.0]\n";
    let text = TWO_BLOCKS.replace("GAP", "10.0e-3") + punch;
    let scene = parse_scene(&text, "blocks.toml").unwrap();
    let tlsph_io::DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(model.effects.walls[0].shape, WallShape::Plane);
    assert_eq!(
        model.effects.walls[1].shape,
        WallShape::Disc { radius: 2.0e-3 }
    );
    // Lowered into the block by 1 mm: the rows under its face start behind it...
    let sunk = text.replace("point = [5.0e-3, 10.0e-3]", "point = [5.0e-3, 9.0e-3]");
    let e = error_of(&sunk);
    assert_eq!(e.field, "wall[punch].point", "{e}");
    assert!(
        e.message.contains("body `left` starts behind the wall")
            && e.message.contains("far side of the disc"),
        "{e}"
    );
    // ... but beside the block, with the block's rows behind its plane and outside its
    // footprint, it is accepted (an unbounded plane there would be refused).
    let beside = text.replace("point = [5.0e-3, 10.0e-3]", "point = [-3.0e-3, 9.0e-3]");
    parse_scene(&beside, "blocks.toml").unwrap();
    let unbounded = beside.replace("radius = 2.0e-3\n", "");
    assert_eq!(error_of(&unbounded).field, "wall[punch].point");
    // Bad radii, and a 1D scene, are refused at the key.
    for (radius, fragment) in [("0.0", "> 0"), ("-1.0e-3", "> 0")] {
        let bad = text.replace("radius = 2.0e-3", &format!("radius = {radius}"));
        let e = error_of(&bad);
        assert_eq!(e.field, "wall[punch].radius", "{e}");
        assert!(e.message.contains(fragment), "{e}");
        assert_eq!(e.line, Some(line_of(&bad, &format!("radius = {radius}"))));
    }
    let rod = "[simulation]\ndimension = 1\nformulation = \"total-lagrangian-corrected\"\nkernel = \"cubic-spline\"\nsmoothing_factor = 1.2\ncfl = 0.3\nend_time = 1.0\n\n[[material]]\nname = \"m\"\nmodel = \"linear-elastic\"\ndensity = 1.0\nyoungs_modulus = 1.0\npoisson_ratio = 0.0\n\n[[body]]\nname = \"rod\"\nmaterial = \"m\"\nspacing = 0.1\nbox = { min = [0.0], max = [1.0] }\n\n[[wall]]\nname = \"end\"\npoint = [0.0]\nnormal = [1.0]\nradius = 1.0\n";
    let e = error_of(rod);
    assert_eq!(e.field, "wall[end].radius", "{e}");
    assert!(e.message.contains("2D or 3D"), "{e}");
}

#[test]
fn a_finite_wall_across_a_symmetry_plane_must_be_centred_on_it_and_stay() {
    // Half model about x = 0 of a block under a punch of half-length 2 mm.
    let half = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[symmetry_plane]]\naxis = \"x\"\nposition = 0.0\n"
        + "\n[[wall]]\nname = \"punch\"\npoint = [CENTRE, 10.0e-3]\nnormal = [0.0, -1.0]\nradius = 2.0e-3\nvelocity = [VX, -1.0]\n";
    let with = |centre: &str, vx: &str| half.replace("CENTRE", centre).replace("VX", vx);
    parse_scene(&with("0.0", "0.0"), "half.toml").unwrap();
    // Clear of the plane it may sit anywhere and slide.
    parse_scene(&with("5.0e-3", "1.0"), "half.toml").unwrap();
    for (centre, vx) in [("1.0e-3", "0.0"), ("0.0", "1.0")] {
        let text = with(centre, vx);
        let e = error_of(&text);
        assert_eq!(e.field, "wall[punch].radius", "{centre}, {vx}: {e}");
        assert!(e.message.contains("symmetry plane x = 0"), "{e}");
    }
}

#[test]
fn a_ball_wall_is_read_and_its_keys_are_checked() {
    // A ball of radius 4 mm resting on the left block's top face (centre 4 mm above it).
    let ball = "\n[[wall]]\nname = \"indenter\"\nshape = \"ball\"\npoint = [5.0e-3, 14.0e-3]\nradius = 4.0e-3\nvelocity = [0.0, -1.0]\n";
    let text = TWO_BLOCKS.replace("GAP", "10.0e-3") + ball;
    let scene = parse_scene(&text, "blocks.toml").unwrap();
    let tlsph_io::DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(
        model.effects.walls[1].shape,
        WallShape::Ball { radius: 4.0e-3 }
    );
    // Lowered by 2 mm its centre region holds particles of the block: refused at `point`.
    let sunk = text.replace("point = [5.0e-3, 14.0e-3]", "point = [5.0e-3, 12.0e-3]");
    let e = error_of(&sunk);
    assert_eq!(e.field, "wall[indenter].point", "{e}");
    assert!(e.message.contains("starts inside the ball"), "{e}");
    // A normal on a ball, no radius for it, a radius on a plane, an unknown shape.
    for (from, to, field, fragment) in [
        (
            "shape = \"ball\"\n",
            "shape = \"ball\"\nnormal = [0.0, -1.0]\n",
            "wall[indenter].normal",
            "has no normal",
        ),
        ("radius = 4.0e-3\n", "", "wall[indenter].radius", "required"),
        (
            "shape = \"ball\"\n",
            "shape = \"plane\"\nnormal = [0.0, -1.0]\n",
            "wall[indenter].radius",
            "has no radius",
        ),
        (
            "shape = \"ball\"",
            "shape = \"pyramid\"",
            "wall[indenter].shape",
            "pyramid",
        ),
    ] {
        let bad = text.replacen(from, to, 1);
        assert_ne!(bad, text);
        let e = error_of(&bad);
        assert_eq!(e.field, field, "{to}: {e}");
        assert!(e.message.contains(fragment), "{to}: {e}");
    }
    // A plane or disc needs its normal.
    let plane = TWO_BLOCKS
        .replace("GAP", "10.0e-3")
        .replace("normal = [0.0, 1.0]\n", "");
    assert_eq!(error_of(&plane).field, "wall[floor].normal");
    // About a symmetry plane x = 0 the ball must be centred on it.
    let half = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[symmetry_plane]]\naxis = \"x\"\nposition = 0.0\n"
        + &ball.replace("point = [5.0e-3, 14.0e-3]", "point = [CX, 14.0e-3]");
    parse_scene(&half.replace("CX", "0.0"), "half.toml").unwrap();
    let e = error_of(&half.replace("CX", "1.0e-3"));
    assert_eq!(e.field, "wall[indenter].radius", "{e}");
    assert!(
        e.message
            .contains("the ball crosses the symmetry plane x = 0"),
        "{e}"
    );
}

/// A 3D beam 20 × 4 × 4 mm on the floor z = 0, with a roller of radius 3 mm lying across its
/// top face (axis along y, centre 3 mm above the face) and a symmetry plane at x = 0 through
/// the roller's axis: half of a three-point bend.
const HALF_BEND: &str = r#"
[simulation]
dimension = 3
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.0e-6

[[material]]
name = "steel"
model = "linear-elastic"
density = 7850.0
youngs_modulus = 200.0e9
poisson_ratio = 0.3

[[body]]
name = "beam"
material = "steel"
spacing = 1.0e-3
box = { min = [0.0, 0.0, 0.0], max = [20.0e-3, 4.0e-3, 4.0e-3] }

[[symmetry_plane]]
axis = "x"
position = 0.0

[[wall]]
name = "roller"
shape = "cylinder"
point = [0.0, 2.0e-3, 7.0e-3]
axis = [0.0, 1.0, 0.0]
radius = 3.0e-3
velocity = [0.0, 0.0, -1.0]
"#;

#[test]
fn a_cylinder_wall_is_read_and_its_keys_are_checked() {
    let scene = parse_scene(HALF_BEND, "bend.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert_eq!(
        model.effects.walls[0].shape,
        WallShape::Cylinder {
            radius: 3.0e-3,
            axis: tlsph_math::Vector::<3>::new(0.0, 1.0, 0.0),
            length: None,
        }
    );
    // Lowered by 2 mm its axis is closer than R to the top layer: refused at `point`.
    let sunk = HALF_BEND.replace(
        "point = [0.0, 2.0e-3, 7.0e-3]",
        "point = [0.0, 2.0e-3, 5.0e-3]",
    );
    let e = error_of(&sunk);
    assert_eq!(e.field, "wall[roller].point", "{e}");
    assert!(
        e.message.contains("starts inside the cylinder") && e.message.contains("from the axis"),
        "{e}"
    );
    // No axis, an axis that is zero, a normal on a cylinder, an axis on a ball, no radius.
    for (from, to, field, fragment) in [
        (
            "axis = [0.0, 1.0, 0.0]\n",
            "",
            "wall[roller].axis",
            "required",
        ),
        (
            "axis = [0.0, 1.0, 0.0]",
            "axis = [0.0, 0.0, 0.0]",
            "wall[roller].axis",
            "zero",
        ),
        (
            "shape = \"cylinder\"\n",
            "shape = \"cylinder\"\nnormal = [0.0, 0.0, -1.0]\n",
            "wall[roller].normal",
            "has no normal",
        ),
        (
            "shape = \"cylinder\"",
            "shape = \"ball\"",
            "wall[roller].axis",
            "only a cylinder",
        ),
        ("radius = 3.0e-3\n", "", "wall[roller].radius", "required"),
    ] {
        let bad = HALF_BEND.replacen(from, to, 1);
        assert_ne!(bad, HALF_BEND);
        let e = error_of(&bad);
        assert_eq!(e.field, field, "{to}: {e}");
        assert!(e.message.contains(fragment), "{to}: {e}");
        assert!(e.line.is_some(), "{e}");
    }
    // A 2D scene has no cylinder (the ball is one in plane strain).
    let flat = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[wall]]\nname = \"roller\"\nshape = \"cylinder\"\npoint = [5.0e-3, 14.0e-3]\naxis = [0.0, 1.0]\nradius = 4.0e-3\n";
    let e = error_of(&flat);
    assert_eq!(e.field, "wall[roller].shape", "{e}");
    assert!(
        e.message.contains("3D") && e.message.contains("ball"),
        "{e}"
    );
}

#[test]
fn a_cylinder_across_a_symmetry_plane_must_be_its_own_mirror_image() {
    // Along the plane x = 0: centred on it (the half bend) and moving along it is accepted;
    // off it, or moving across it, is refused.
    for (from, to) in [
        ("point = [0.0, ", "point = [1.0e-3, "),
        ("velocity = [0.0, 0.0, -1.0]", "velocity = [1.0, 0.0, -1.0]"),
    ] {
        let bad = HALF_BEND.replacen(from, to, 1);
        let e = error_of(&bad);
        assert_eq!(e.field, "wall[roller].radius", "{to}: {e}");
        assert!(
            e.message
                .contains("the cylinder crosses the symmetry plane x = 0"),
            "{e}"
        );
    }
    // Along the plane's normal (axis x) the infinite cylinder is its own mirror image
    // anywhere; it may slide along its axis unless it has friction.
    let along_x = HALF_BEND
        .replace(
            "point = [0.0, 2.0e-3, 7.0e-3]",
            "point = [5.0e-3, 2.0e-3, 7.0e-3]",
        )
        .replace("axis = [0.0, 1.0, 0.0]", "axis = [2.0, 0.0, 0.0]")
        .replace("velocity = [0.0, 0.0, -1.0]", "velocity = [1.0, 0.0, -1.0]");
    parse_scene(&along_x, "bend.toml").unwrap();
    let rubbing = along_x.replace("radius = 3.0e-3\n", "radius = 3.0e-3\nfriction = 0.2\n");
    let e = error_of(&rubbing);
    assert_eq!(e.field, "wall[roller].velocity", "{e}");
    assert!(e.message.contains("friction would drag"), "{e}");
    assert_eq!(
        e.line,
        Some(line_of(&rubbing, "velocity = [1.0, 0.0, -1.0]"))
    );
    // An oblique axis always crosses the plane.
    let oblique = HALF_BEND.replace("axis = [0.0, 1.0, 0.0]", "axis = [1.0, 1.0, 0.0]");
    let e = error_of(&oblique);
    assert_eq!(e.field, "wall[roller].axis", "{e}");
    assert_eq!(e.line, Some(line_of(&oblique, "axis = [1.0, 1.0, 0.0]")));
    assert!(e.message.contains("oblique"), "{e}");
}

#[test]
fn a_finite_cylinder_is_read_placed_and_checked() {
    // `length` makes the roller a solid cylinder of that length centred at its point.
    let short = HALF_BEND.replace("radius = 3.0e-3\n", "radius = 3.0e-3\nlength = 6.0e-3\n");
    let scene = parse_scene(&short, "short.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert_eq!(
        model.effects.walls[0].shape,
        WallShape::Cylinder {
            radius: 3.0e-3,
            axis: tlsph_math::Vector::<3>::new(0.0, 1.0, 0.0),
            length: Some(6.0e-3),
        }
    );
    // Not positive: refused at `length`, with its line.
    let flat = short.replace("length = 6.0e-3", "length = 0.0");
    let e = error_of(&flat);
    assert_eq!(e.field, "wall[roller].length", "{e}");
    assert!(e.message.contains("> 0"), "{e}");
    assert_eq!(e.line, Some(line_of(&flat, "length = 0.0")));
    // Only a cylinder has a length.
    let ball = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[wall]]\nname = \"ball\"\nshape = \"ball\"\npoint = [5.0e-3, 14.0e-3]\nradius = 4.0e-3\nlength = 1.0e-3\n";
    let e = error_of(&ball);
    assert_eq!(e.field, "wall[ball].length", "{e}");
    assert!(e.message.contains("only a cylinder"), "{e}");
    // Sunk 2 mm into the beam's top layer it starts inside while it spans the beam's width
    // (y from 0 to 4 mm); moved along its axis to span y = 6–12 mm it is clear of the beam.
    let sunk = short.replace(
        "point = [0.0, 2.0e-3, 7.0e-3]",
        "point = [0.0, 2.0e-3, 5.0e-3]",
    );
    let e = error_of(&sunk);
    assert_eq!(e.field, "wall[roller].point", "{e}");
    assert!(e.message.contains("starts inside the cylinder"), "{e}");
    parse_scene(
        &short.replace(
            "point = [0.0, 2.0e-3, 7.0e-3]",
            "point = [0.0, 9.0e-3, 5.0e-3]",
        ),
        "beside.toml",
    )
    .unwrap();
    // Along the symmetry plane's normal (axis x) it reaches L/2 = 3 mm to either side of its
    // point: clear of the plane (point at x = 5 mm) or centred on it is accepted; crossing it
    // off centre (x = 2 mm), or centred but sliding across it, is refused.
    let along_x = |x: &str, velocity: &str| {
        short
            .replace(
                "point = [0.0, 2.0e-3, 7.0e-3]",
                &format!("point = [{x}, 2.0e-3, 7.0e-3]"),
            )
            .replace("axis = [0.0, 1.0, 0.0]", "axis = [2.0, 0.0, 0.0]")
            .replace("velocity = [0.0, 0.0, -1.0]", velocity)
    };
    parse_scene(
        &along_x("5.0e-3", "velocity = [1.0, 0.0, -1.0]"),
        "clear.toml",
    )
    .unwrap();
    parse_scene(
        &along_x("0.0", "velocity = [0.0, 0.0, -1.0]"),
        "centred.toml",
    )
    .unwrap();
    for (x, velocity) in [
        ("2.0e-3", "velocity = [0.0, 0.0, -1.0]"),
        ("0.0", "velocity = [1.0, 0.0, -1.0]"),
    ] {
        let e = error_of(&along_x(x, velocity));
        assert_eq!(e.field, "wall[roller].radius", "{x}, {velocity}: {e}");
        assert!(
            e.message
                .contains("the cylinder crosses the symmetry plane x = 0"),
            "{e}"
        );
    }
    // Oblique (axis (1, 1, 0)): it reaches ½L cos 45° + R sin 45° = 4.2 mm along x, so at
    // x = 5 mm it is clear of the plane, at x = 4 mm it crosses it.
    let oblique = |x: &str| {
        short
            .replace(
                "point = [0.0, 2.0e-3, 7.0e-3]",
                &format!("point = [{x}, 2.0e-3, 7.0e-3]"),
            )
            .replace("axis = [0.0, 1.0, 0.0]", "axis = [1.0, 1.0, 0.0]")
    };
    parse_scene(&oblique("5.0e-3"), "oblique.toml").unwrap();
    let e = error_of(&oblique("4.0e-3"));
    assert_eq!(e.field, "wall[roller].axis", "{e}");
    assert!(
        e.message.contains("oblique") && e.message.contains("keep it clear"),
        "{e}"
    );
}

#[test]
fn a_box_wall_is_read_placed_and_checked() {
    // A die over the half beam: a block 6 × 6 × 4 mm centred on the symmetry plane x = 0, its
    // bottom face 4 mm up, on the beam's top face; edges along x, y, z without a normal.
    let die = HALF_BEND.replace(
        "shape = \"cylinder\"\npoint = [0.0, 2.0e-3, 7.0e-3]\naxis = [0.0, 1.0, 0.0]\nradius = 3.0e-3\n",
        "shape = \"box\"\npoint = [0.0, 2.0e-3, 6.0e-3]\nsize = [6.0e-3, 6.0e-3, 4.0e-3]\n",
    );
    assert!(die.contains("shape = \"box\""));
    let scene = parse_scene(&die, "die.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    let wall = &model.effects.walls[0];
    assert_eq!(
        wall.shape,
        WallShape::Box {
            size: tlsph_math::Vector::<3>::new(6.0e-3, 6.0e-3, 4.0e-3),
            axis: tlsph_math::Vector::<3>::x(),
            edge_radius: 0.0,
        }
    );
    assert_eq!(wall.normal, tlsph_math::Vector::<3>::z());
    let refused = |text: &str, field: &str, needle: &str, line: &str| {
        let e = error_of(text);
        assert_eq!(e.field, format!("wall[roller].{field}"), "{e}");
        assert!(e.message.contains(needle), "{e}");
        assert_eq!(e.line, Some(line_of(text, line)), "{e}");
    };
    let size_line = "size = [6.0e-3, 6.0e-3, 4.0e-3]";
    // Sunk 1 mm into the beam: its top layer (z = 3.5 mm) starts inside.
    let sunk = die.replace(
        "point = [0.0, 2.0e-3, 6.0e-3]",
        "point = [0.0, 2.0e-3, 5.0e-3]",
    );
    refused(
        &sunk,
        "point",
        "starts inside the box",
        "point = [0.0, 2.0e-3, 5.0e-3]",
    );
    // Its keys: a size is required, positive, and only a box's; a box has no radius.
    let no_size = die.replace(&format!("{size_line}\n"), "");
    refused(&no_size, "size", "is required by a box", "shape = \"box\"");
    let flat = die.replace(size_line, "size = [6.0e-3, 0.0, 4.0e-3]");
    refused(&flat, "size", "> 0", "size = [6.0e-3, 0.0, 4.0e-3]");
    let rounded = die.replace(size_line, &format!("{size_line}\nradius = 1.0e-3"));
    refused(&rounded, "radius", "not a radius", "radius = 1.0e-3");
    let ball = HALF_BEND
        .replace("shape = \"cylinder\"", "shape = \"ball\"")
        .replace("axis = [0.0, 1.0, 0.0]", "size = [1.0, 1.0, 1.0]");
    refused(&ball, "size", "only a box", "size = [1.0, 1.0, 1.0]");
    // Turned in 3D by its normal and its axis together, at right angles.
    let normal_only = die.replace(size_line, &format!("{size_line}\nnormal = [0.0, 0.0, 1.0]"));
    refused(
        &normal_only,
        "normal",
        "give both",
        "normal = [0.0, 0.0, 1.0]",
    );
    let axis_only = die.replace(size_line, &format!("{size_line}\naxis = [1.0, 0.0, 0.0]"));
    refused(&axis_only, "axis", "give both", "axis = [1.0, 0.0, 0.0]");
    let turned = |axis: &str, x: &str| {
        die.replace(
            size_line,
            &format!("{size_line}\nnormal = [0.0, 0.0, 1.0]\naxis = {axis}"),
        )
        .replace(
            "point = [0.0, 2.0e-3, 6.0e-3]",
            &format!("point = [{x}, 2.0e-3, 6.0e-3]"),
        )
    };
    refused(
        &turned("[1.0, 0.0, 0.5]", "0.0"),
        "axis",
        "right angles",
        "axis = [1.0, 0.0, 0.5]",
    );
    parse_scene(&turned("[1.0, 0.0, 0.0]", "0.0"), "square.toml").unwrap();
    // Across the symmetry plane x = 0: its own mirror image only with a face parallel to the
    // plane, centred on it and not sliding across it. Turned 45° about z it reaches
    // 3√2 = 4.24 mm along x: clear at x = 4.5 mm, crossing at x = 4 mm.
    let off_centre = die.replace(
        "point = [0.0, 2.0e-3, 6.0e-3]",
        "point = [1.0e-3, 2.0e-3, 6.0e-3]",
    );
    refused(
        &off_centre,
        "size",
        "the box crosses the symmetry plane x = 0",
        size_line,
    );
    let across = die.replace("velocity = [0.0, 0.0, -1.0]", "velocity = [1.0, 0.0, -1.0]");
    refused(
        &across,
        "size",
        "the box crosses the symmetry plane x = 0",
        size_line,
    );
    parse_scene(&turned("[1.0, 1.0, 0.0]", "4.5e-3"), "clear.toml").unwrap();
    let askew = turned("[1.0, 1.0, 0.0]", "4.0e-3");
    refused(
        &askew,
        "normal",
        "none of its faces is parallel",
        "normal = [0.0, 0.0, 1.0]",
    );
    // Rounded to 1 mm it reaches only 2√2 + 1 = 3.83 mm: clear at x = 4 mm.
    let rounded_askew = askew.replace(size_line, &format!("{size_line}\nedge_radius = 1.0e-3"));
    parse_scene(&rounded_askew, "rounded-askew.toml").unwrap();
    // Its edges rounded: a radius up to half the shortest edge, and only on a box.
    let rounded = die.replace(size_line, &format!("{size_line}\nedge_radius = 1.0e-3"));
    let scene = parse_scene(&rounded, "rounded.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert!(matches!(
        model.effects.walls[0].shape,
        WallShape::Box { edge_radius, .. } if edge_radius == 1.0e-3
    ));
    let too_round = die.replace(size_line, &format!("{size_line}\nedge_radius = 2.5e-3"));
    refused(
        &too_round,
        "edge_radius",
        "at most half",
        "edge_radius = 2.5e-3",
    );
    let not_a_number = die.replace(size_line, &format!("{size_line}\nedge_radius = nan"));
    refused(
        &not_a_number,
        "edge_radius",
        "finite number ≥ 0",
        "edge_radius = nan",
    );
    let round_ball = ball.replace("size = [1.0, 1.0, 1.0]", "edge_radius = 1.0e-3");
    refused(
        &round_ball,
        "edge_radius",
        "only a box",
        "edge_radius = 1.0e-3",
    );
    // Over the beam's far top edge (x = 20 mm, z = 4 mm), 0.2 mm into the particle at
    // (19.5, y, 3.5) mm both ways: that particle starts inside the sharp box, but outside the
    // box rounded to 1 mm (0.13 mm clear of its rounded edge).
    let over_the_edge = |keys: &str| {
        die.replace(
            "point = [0.0, 2.0e-3, 6.0e-3]",
            "point = [22.3e-3, 2.0e-3, 5.3e-3]",
        )
        .replace(size_line, &format!("{size_line}\n{keys}"))
    };
    refused(
        &over_the_edge(""),
        "point",
        "starts inside the box",
        "point = [22.3e-3, 2.0e-3, 5.3e-3]",
    );
    parse_scene(&over_the_edge("edge_radius = 1.0e-3"), "rounded-edge.toml").unwrap();
    // A box cannot spin.
    let spun = die.replace(
        size_line,
        &format!("{size_line}\nfriction = 0.2\nspin = 10.0"),
    );
    refused(&spun, "spin", "a box cannot spin", "spin = 10.0");
    // In 2D a rectangle, turned by its normal alone: an axis is refused.
    let rectangle = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[wall]]\nname = \"roller\"\nshape = \"box\"\npoint = [5.0e-3, 14.0e-3]\nsize = [4.0e-3, 2.0e-3]\nnormal = [1.0, 2.0]\n";
    let scene = parse_scene(&rectangle, "rectangle.toml").unwrap();
    let tlsph_io::DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(
        model.effects.walls[1].normal,
        tlsph_math::Vector::<2>::new(1.0, 2.0)
    );
    let with_axis = rectangle.replace(
        "normal = [1.0, 2.0]",
        "normal = [1.0, 2.0]\naxis = [1.0, 0.0]",
    );
    refused(&with_axis, "axis", "a box in 3D", "axis = [1.0, 0.0]");
}

#[test]
fn a_spin_is_read_about_the_walls_own_axis_and_checked() {
    // The half bend without its symmetry plane: the roller spins about its axis (y).
    let whole = HALF_BEND.replace("[[symmetry_plane]]\naxis = \"x\"\nposition = 0.0\n", "");
    assert_ne!(whole, HALF_BEND);
    let spinning = whole.replace(
        "velocity = [0.0, 0.0, -1.0]",
        "friction = 0.3\nspin = 20.0\nspin_ramp_time = 1.0e-7",
    );
    let scene = parse_scene(&spinning, "spin.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    let motion = model.effects.walls[0].motion.as_ref().unwrap();
    assert_eq!(motion.spin, Some(tlsph_math::Vector3::new(0.0, 20.0, 0.0)));
    assert_eq!(motion.velocity, tlsph_math::Vector::<3>::zeros());
    assert_eq!(
        motion.spin_ramp,
        Some(tlsph_solver::VelocityRamp {
            duration: 1.0e-7,
            shape: tlsph_solver::RampShape::Smooth
        })
    );
    assert!(motion.amplitude.is_none());
    // In 2D a ball spins about z.
    let ball = TWO_BLOCKS.replace("GAP", "10.0e-3")
        + "\n[[wall]]\nname = \"roll\"\nshape = \"ball\"\npoint = [5.0e-3, 16.0e-3]\nradius = 5.0e-3\nfriction = 0.5\nspin = -3.0\n";
    let scene = parse_scene(&ball, "roll.toml").unwrap();
    let tlsph_io::DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    let spin = model.effects.walls[1].motion.as_ref().unwrap().spin;
    assert_eq!(spin, Some(tlsph_math::Vector3::new(0.0, 0.0, -3.0)));
    // What cannot spin, or would not be felt, or would break the mirror symmetry.
    for (text, field, fragment) in [
        (
            whole.replace("velocity = [0.0, 0.0, -1.0]", "spin = 20.0"),
            "wall[roller].spin",
            "only through friction",
        ),
        (
            spinning
                .replace("shape = \"cylinder\"", "shape = \"ball\"")
                .replace("axis = [0.0, 1.0, 0.0]\n", ""),
            "wall[roller].spin",
            "needs an `axis`",
        ),
        (
            HALF_BEND.replace("velocity = [0.0, 0.0, -1.0]", "friction = 0.3\nspin = 20.0"),
            "wall[roller].spin",
            "not about the normal of the symmetry plane x = 0",
        ),
        (
            TWO_BLOCKS.replace("GAP", "10.0e-3") + "friction = 0.5\nspin = 1.0\n",
            "wall[floor].spin",
            "only a ball may spin",
        ),
        (
            ball.replace("spin = -3.0", "spin = nan"),
            "wall[roll].spin",
            "finite",
        ),
        (
            ball.replace("spin = -3.0", "spin = -3.0\nramp_time = 1.0"),
            "wall[roll].ramp_time",
            "`spin_ramp_time`",
        ),
        (
            TWO_BLOCKS.replace("GAP", "10.0e-3") + "spin_ramp_time = 1.0\n",
            "wall[floor].spin_ramp_time",
            "needs a `spin`",
        ),
    ] {
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(e.message.contains(fragment), "{e}");
        assert!(e.line.is_some(), "{e}");
    }
}

#[test]
fn a_cone_wall_is_read_placed_and_checked() {
    // A 120° cone (half-angle 60°) over the half beam, its tip on the beam's top face (z = 4
    // mm) and on the symmetry plane x = 0, its axis pointing up into the cone.
    let cone_lines = "shape = \"cone\"\npoint = [0.0, 2.0e-3, 4.0e-3]\naxis = [0.0, 0.0, 1.0]\nhalf_angle = 60.0\n";
    let cone = HALF_BEND.replace(
        "shape = \"cylinder\"\npoint = [0.0, 2.0e-3, 7.0e-3]\naxis = [0.0, 1.0, 0.0]\nradius = 3.0e-3\n",
        cone_lines,
    );
    assert!(cone.contains(cone_lines));
    let scene = parse_scene(&cone, "cone.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert_eq!(
        model.effects.walls[0].shape,
        WallShape::Cone {
            axis: tlsph_math::Vector::<3>::z(),
            half_angle: 60f64.to_radians(),
            tip_radius: 0.0,
        }
    );
    let refused = |text: &str, field: &str, needle: &str, line: &str| {
        let e = error_of(text);
        assert_eq!(e.field, format!("wall[roller].{field}"), "{e}");
        assert!(e.message.contains(needle), "{e}");
        assert_eq!(e.line, Some(line_of(text, line)), "{e}");
    };
    // Sunk 1 mm: the top layer's particles nearest the axis (0.71 mm from it, 0.5 mm above
    // the tip) are inside the flanks (they are 0.25 mm inside).
    let sunk = cone.replace(
        "point = [0.0, 2.0e-3, 4.0e-3]",
        "point = [0.0, 2.0e-3, 3.0e-3]",
    );
    refused(
        &sunk,
        "point",
        "starts inside the cone",
        "point = [0.0, 2.0e-3, 3.0e-3]",
    );
    // Its keys: a half-angle is required, within 0–90°; a tip radius ≥ 0; no radius, no
    // normal; an axis is required. A half-angle or a tip radius on another shape is refused.
    let angle = "half_angle = 60.0";
    let no_angle = cone.replace(&format!("{angle}\n"), "");
    refused(
        &no_angle,
        "half_angle",
        "is required by a cone",
        "shape = \"cone\"",
    );
    for bad in ["90.0", "0.0", "-30.0", "nan"] {
        let text = cone.replace(angle, &format!("half_angle = {bad}"));
        refused(
            &text,
            "half_angle",
            "between 0 and 90",
            &format!("half_angle = {bad}"),
        );
    }
    let with = |extra: &str| cone.replace(angle, &format!("{angle}\n{extra}"));
    refused(
        &with("tip_radius = -1.0e-3"),
        "tip_radius",
        "≥ 0",
        "tip_radius = -1.0e-3",
    );
    refused(
        &with("radius = 1.0e-3"),
        "radius",
        "not a radius",
        "radius = 1.0e-3",
    );
    refused(
        &with("normal = [0.0, 0.0, 1.0]"),
        "normal",
        "has no normal",
        "normal = [0.0, 0.0, 1.0]",
    );
    let no_axis = cone.replace("axis = [0.0, 0.0, 1.0]\n", "");
    refused(
        &no_axis,
        "axis",
        "is required by a cylinder, cone or pyramid",
        "shape = \"cone\"",
    );
    let roller_angle = HALF_BEND.replace("radius = 3.0e-3", "radius = 3.0e-3\nhalf_angle = 60.0");
    refused(
        &roller_angle,
        "half_angle",
        "only a cone",
        "half_angle = 60.0",
    );
    let roller_tip = HALF_BEND.replace("radius = 3.0e-3", "radius = 3.0e-3\ntip_radius = 1.0e-3");
    refused(
        &roller_tip,
        "tip_radius",
        "only a cone",
        "tip_radius = 1.0e-3",
    );
    // Rounded, the tip stays at `point` (it starts just touching the top face).
    let scene = parse_scene(&with("tip_radius = 0.2e-3"), "rockwell.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert!(matches!(
        model.effects.walls[0].shape,
        WallShape::Cone { tip_radius, .. } if tip_radius == 0.2e-3
    ));
    // Across the symmetry plane x = 0: its own mirror image only with its axis along the
    // plane, its tip on it and not sliding across it.
    let off_plane = cone.replace(
        "point = [0.0, 2.0e-3, 4.0e-3]",
        "point = [1.0e-3, 2.0e-3, 4.0e-3]",
    );
    refused(
        &off_plane,
        "axis",
        "its tip is off the plane or it moves across it",
        "axis = [0.0, 0.0, 1.0]",
    );
    let across = cone.replace("velocity = [0.0, 0.0, -1.0]", "velocity = [1.0, 0.0, -1.0]");
    refused(
        &across,
        "axis",
        "its tip is off the plane or it moves across it",
        "axis = [0.0, 0.0, 1.0]",
    );
    // Otherwise it must point away from the plane within 90° − α of its normal, its rounded
    // tip clear of it: a 30° cone high above the beam along +x, its tip rounded to 1 mm, is
    // clear with the tip 0.5 mm past the plane (the tip sphere's centre 1.5 mm), not with the
    // tip 0.5 mm before it; tipped 45° up it is clear, but not with a half-angle of 50°.
    let aside = |x: &str, axis: &str, half_angle: &str| {
        cone.replace(
            cone_lines,
            &format!("shape = \"cone\"\npoint = [{x}, 2.0e-3, 20.0e-3]\naxis = {axis}\nhalf_angle = {half_angle}\ntip_radius = 1.0e-3\n"),
        )
    };
    parse_scene(&aside("0.5e-3", "[1.0, 0.0, 0.0]", "30.0"), "aside.toml").unwrap();
    parse_scene(&aside("0.5e-3", "[1.0, 0.0, 1.0]", "30.0"), "tipped.toml").unwrap();
    for (x, axis, half_angle) in [
        ("-0.5e-3", "[1.0, 0.0, 0.0]", "30.0"),
        ("0.5e-3", "[1.0, 0.0, 1.0]", "50.0"),
        ("0.5e-3", "[-1.0, 0.0, 3.0]", "10.0"),
    ] {
        refused(
            &aside(x, axis, half_angle),
            "axis",
            "the cone reaches across the symmetry plane x = 0",
            &format!("axis = {axis}"),
        );
    }
}

#[test]
fn a_pyramid_wall_is_read_placed_and_checked() {
    // A Vickers pyramid (4 faces at 68° to its axis) over the half beam, its tip on the beam's
    // top face (z = 4 mm) and on the symmetry plane x = 0, its axis pointing up into it, its
    // first face towards +x.
    let pyramid_lines = "shape = \"pyramid\"\npoint = [0.0, 2.0e-3, 4.0e-3]\naxis = [0.0, 0.0, 1.0]\nsides = 4\nhalf_angle = 68.0\nface_direction = [1.0, 0.0, 0.0]\n";
    let vickers = HALF_BEND.replace(
        "shape = \"cylinder\"\npoint = [0.0, 2.0e-3, 7.0e-3]\naxis = [0.0, 1.0, 0.0]\nradius = 3.0e-3\n",
        pyramid_lines,
    );
    assert!(vickers.contains(pyramid_lines));
    let scene = parse_scene(&vickers, "vickers.toml").unwrap();
    let tlsph_io::DimensionModel::Three(model) = &scene.model else {
        panic!("3D")
    };
    assert_eq!(
        model.effects.walls[0].shape,
        WallShape::Pyramid {
            axis: tlsph_math::Vector::<3>::z(),
            face_direction: tlsph_math::Vector::<3>::x(),
            sides: 4,
            half_angle: 68f64.to_radians(),
            tip_radius: 0.0,
        }
    );
    // Like a box or a cone, in a total-Lagrangian scene without hourglass control it gets a
    // note (`tlsph check`).
    let notes = scene.overview().notes;
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with("wall `roller` is a pyramid")
                && n.contains("[hourglass_control]")),
        "{notes:?}"
    );
    let refused = |text: &str, field: &str, needle: &str, line: &str| {
        let e = error_of(text);
        assert_eq!(e.field, format!("wall[roller].{field}"), "{e}");
        assert!(e.message.contains(needle), "{e}");
        assert_eq!(e.line, Some(line_of(text, line)), "{e}");
    };
    // Sunk 1 mm: the top layer's particles nearest the axis (0.5 mm from it along x and y,
    // 0.5 mm above the tip) are inside all four faces.
    let sunk = vickers.replace(
        "point = [0.0, 2.0e-3, 4.0e-3]",
        "point = [0.0, 2.0e-3, 3.0e-3]",
    );
    refused(
        &sunk,
        "point",
        "starts inside the pyramid",
        "point = [0.0, 2.0e-3, 3.0e-3]",
    );
    // Its keys: `sides` (3 to 100) and `face_direction` (at right angles to the axis) are
    // required; neither is taken by another shape; a pyramid cannot spin and needs 3D.
    let sides = "sides = 4";
    refused(
        &vickers.replace(&format!("{sides}\n"), ""),
        "sides",
        "is required by a pyramid",
        "shape = \"pyramid\"",
    );
    for bad in ["2", "101", "-4"] {
        let text = vickers.replace(sides, &format!("sides = {bad}"));
        refused(&text, "sides", "from 3 to 100", &format!("sides = {bad}"));
    }
    let face = "face_direction = [1.0, 0.0, 0.0]";
    refused(
        &vickers.replace(&format!("{face}\n"), ""),
        "face_direction",
        "is required by a pyramid",
        "shape = \"pyramid\"",
    );
    let slanted = vickers.replace(face, "face_direction = [1.0, 0.0, 0.1]");
    refused(
        &slanted,
        "face_direction",
        "at right angles to its axis",
        "face_direction = [1.0, 0.0, 0.1]",
    );
    refused(
        &vickers.replace("half_angle = 68.0\n", ""),
        "half_angle",
        "is required by a pyramid",
        "shape = \"pyramid\"",
    );
    let roller =
        |extra: &str| HALF_BEND.replace("radius = 3.0e-3", &format!("radius = 3.0e-3\n{extra}"));
    refused(&roller("sides = 4"), "sides", "only a pyramid", "sides = 4");
    refused(&roller(face), "face_direction", "only a pyramid", face);
    let spinning = vickers.replace(sides, "sides = 4\nfriction = 0.3\nspin = 5.0");
    refused(&spinning, "spin", "a pyramid cannot spin", "spin = 5.0");
    let flat = TWO_BLOCKS.replace("GAP", "10.0e-3").replace(
        "point = [0.0, 0.0]\nnormal = [0.0, 1.0]",
        "shape = \"pyramid\"\npoint = [5.0e-3, -1.0e-3]\naxis = [0.0, -1.0]\nhalf_angle = 45.0",
    );
    let e = error_of(&flat);
    assert_eq!(e.field, "wall[floor].shape", "{e}");
    assert!(e.message.contains("needs a 3D scene"), "{e}");
    // Across the symmetry plane x = 0: its own mirror image when the plane passes through the
    // middle of a face (first face towards x) or through an edge (turned 45°), not turned
    // 10°. A Berkovich pyramid (3 faces at 65.27°) is mirrored by a plane through one face's
    // middle and the opposite edge: its first face towards y, not towards x.
    parse_scene(
        &vickers.replace(face, "face_direction = [1.0, 1.0, 0.0]"),
        "edges.toml",
    )
    .unwrap();
    let turned = vickers.replace(face, "face_direction = [0.985, 0.174, 0.0]");
    refused(
        &turned,
        "face_direction",
        "passes through neither the middle of a face nor an edge",
        "face_direction = [0.985, 0.174, 0.0]",
    );
    let berkovich = |direction: &str| {
        vickers
            .replace(sides, "sides = 3")
            .replace("half_angle = 68.0", "half_angle = 65.27")
            .replace(face, &format!("face_direction = {direction}"))
    };
    parse_scene(&berkovich("[0.0, 1.0, 0.0]"), "berkovich.toml").unwrap();
    refused(
        &berkovich("[1.0, 0.0, 0.0]"),
        "face_direction",
        "passes through neither",
        "face_direction = [1.0, 0.0, 0.0]",
    );
    // Off the plane it must not lean back towards it: every edge pointing away, and the tip's
    // sphere clear. High above the beam, its axis along +x, its tip rounded to 1 mm, it is
    // clear with the tip 0.5 mm past the plane (the sphere's centre 1.5 mm), not 0.5 mm
    // before it; tipped 45° up with faces at 40° its edges still point away (the cone through
    // its edges, of half-angle atan(tan 40° / cos 45°) = 49.9°, would not), with faces at 50°
    // one leans back.
    let aside = |x: &str, axis: &str, half_angle: &str| {
        vickers.replace(
            pyramid_lines,
            &format!("shape = \"pyramid\"\npoint = [{x}, 2.0e-3, 20.0e-3]\naxis = {axis}\nsides = 4\nface_direction = [0.0, 1.0, 0.0]\nhalf_angle = {half_angle}\ntip_radius = 1.0e-3\n"),
        )
    };
    parse_scene(&aside("0.5e-3", "[1.0, 0.0, 0.0]", "30.0"), "aside.toml").unwrap();
    parse_scene(&aside("0.5e-3", "[1.0, 0.0, 1.0]", "40.0"), "tipped.toml").unwrap();
    for (x, axis, half_angle) in [
        ("-0.5e-3", "[1.0, 0.0, 0.0]", "30.0"),
        ("0.5e-3", "[1.0, 0.0, 1.0]", "50.0"),
    ] {
        refused(
            &aside(x, axis, half_angle),
            "axis",
            "the pyramid reaches across the symmetry plane x = 0",
            &format!("axis = {axis}"),
        );
    }
}

#[test]
fn a_cone_in_2d_is_a_wedge_that_cannot_spin() {
    // A 90° wedge (half-angle 45°) under the blocks' floor, pointing down and away from them.
    let wedge = TWO_BLOCKS.replace("GAP", "10.0e-3").replace(
        "point = [0.0, 0.0]\nnormal = [0.0, 1.0]",
        "shape = \"cone\"\npoint = [5.0e-3, -1.0e-3]\naxis = [0.0, -1.0]\nhalf_angle = 45.0",
    );
    let scene = parse_scene(&wedge, "wedge.toml").unwrap();
    let tlsph_io::DimensionModel::Two(model) = &scene.model else {
        panic!("2D")
    };
    assert_eq!(
        model.effects.walls[0].shape,
        WallShape::Cone {
            axis: -tlsph_math::Vector::<2>::y(),
            half_angle: 45f64.to_radians(),
            tip_radius: 0.0,
        }
    );
    // Turned up, it opens into the blocks.
    let into = wedge.replace("axis = [0.0, -1.0]", "axis = [0.0, 1.0]");
    let e = error_of(&into);
    assert_eq!(e.field, "wall[floor].point", "{e}");
    assert!(e.message.contains("starts inside the cone"), "{e}");
    let spinning = wedge.replace(
        "half_angle = 45.0",
        "half_angle = 45.0\nfriction = 0.3\nspin = 5.0",
    );
    let e = error_of(&spinning);
    assert_eq!(e.field, "wall[floor].spin", "{e}");
    assert!(e.message.contains("only a ball may spin"), "{e}");
}
