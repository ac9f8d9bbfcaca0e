//! Where bodies start: two bodies that start inside each other, a body that starts behind a
//! rigid wall, or bodies on both sides of a symmetry plane are refused by `tlsph check` at
//! their line, naming the bodies (and a particle).

use super::{error_of, line_of};
use tlsph_io::parse_scene;

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
