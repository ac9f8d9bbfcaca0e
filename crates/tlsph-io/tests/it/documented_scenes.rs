//! The scenes docs/scene-format.md shows whole (every `toml` block with a `[simulation]`
//! table) are read without error and set up a simulation, so a user who copies one starts from
//! a scene that works.

use tlsph_io::{parse_scene, DimensionModel};
use tlsph_solver::Simulation;

const DOC: &str = include_str!("../../../../docs/scene-format.md");

/// The `toml` code blocks of the document, in order.
fn toml_blocks() -> Vec<&'static str> {
    let mut blocks = Vec::new();
    let mut rest = DOC;
    while let Some(start) = rest.find("```toml\n") {
        let body = &rest[start + "```toml\n".len()..];
        let end = body.find("```").expect("every toml block is closed");
        blocks.push(&body[..end]);
        rest = &body[end + 3..];
    }
    blocks
}

/// Reads `text` and builds its simulation; a failure names the block.
fn set_up(text: &str, what: &str) {
    let scene = parse_scene(text, "doc.toml").unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
    let result = match scene.model {
        DimensionModel::One(m) => Simulation::new(m).map(|_| ()),
        DimensionModel::Two(m) => Simulation::new(m).map(|_| ()),
        DimensionModel::Three(m) => Simulation::new(m).map(|_| ()),
    };
    if let Err(e) = result {
        panic!("{what}: set-up failed: {e}\n{text}");
    }
}

#[test]
fn every_whole_scene_in_the_scene_format_document_reads_and_sets_up() {
    let whole: Vec<&str> = toml_blocks()
        .into_iter()
        .filter(|b| b.contains("[simulation]"))
        .collect();
    // The complete example, the Taylor bar, the copper plate impact and the others: the count
    // guards the extraction itself.
    assert!(whole.len() >= 17, "found {} whole scenes", whole.len());
    for (k, text) in whole.iter().enumerate() {
        set_up(text, &format!("whole scene {k}"));
    }
}
