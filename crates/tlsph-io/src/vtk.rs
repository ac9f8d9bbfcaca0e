//! Particle frames as VTK XML unstructured grids (`.vtu`, one vertex cell per particle) and a
//! ParaView collection (`.pvd`) indexing them by time. Data arrays are stored inline as
//! base64-encoded little-endian binary, which ParaView and VisIt read without extra libraries.

use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// One named per-particle array of a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameArray {
    /// Array name shown in ParaView (e.g. `velocity`).
    pub name: String,
    /// Components per particle: 1 (scalar), 3 (vector) or 9 (tensor, row-major).
    pub components: usize,
    /// `components` values per particle, particle after particle.
    pub values: Vec<f64>,
}

/// The particles of one instant, always in 3D (1D and 2D runs are padded with zeros).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    /// Simulated time \[s\].
    pub time: f64,
    /// Current positions.
    pub positions: Vec<[f64; 3]>,
    /// Point data.
    pub arrays: Vec<FrameArray>,
}

/// Writes `frame` as a `.vtu` file (through a temporary file and a rename).
pub fn write_vtu(path: &Path, frame: &Frame) -> std::io::Result<()> {
    let n = frame.positions.len();
    for a in &frame.arrays {
        if a.values.len() != n * a.components {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "array `{}` has {} values for {n} particles × {} components",
                    a.name,
                    a.values.len(),
                    a.components
                ),
            ));
        }
    }
    let mut xml = String::with_capacity(64 * n + 1024);
    xml.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    let _ = writeln!(xml, "<FieldData><DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">{:e}</DataArray></FieldData>", frame.time);
    let _ = writeln!(xml, "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">");
    xml.push_str("<PointData>\n");
    for a in &frame.arrays {
        let _ = write!(
            xml,
            "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">",
            escape(&a.name),
            a.components
        );
        push_f64_block(&mut xml, &a.values);
        xml.push_str("</DataArray>\n");
    }
    xml.push_str("</PointData>\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"binary\">");
    let flat: Vec<f64> = frame.positions.iter().flatten().copied().collect();
    push_f64_block(&mut xml, &flat);
    xml.push_str("</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">");
    let ids: Vec<i64> = (0..n as i64).collect();
    push_block(
        &mut xml,
        &ids.iter()
            .flat_map(|i| i.to_le_bytes())
            .collect::<Vec<u8>>(),
    );
    xml.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">");
    let offsets: Vec<i64> = (1..=n as i64).collect();
    push_block(
        &mut xml,
        &offsets
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect::<Vec<u8>>(),
    );
    xml.push_str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">");
    // VTK_VERTEX = 1.
    push_block(&mut xml, &vec![1u8; n]);
    xml.push_str("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    write_atomically(path, xml.as_bytes())
}

/// Writes a ParaView collection listing `(time, file)` pairs (file names relative to the
/// collection's folder).
pub fn write_pvd(path: &Path, entries: &[(f64, PathBuf)]) -> std::io::Result<()> {
    let mut xml = String::from("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n");
    for (t, file) in entries {
        let _ = writeln!(
            xml,
            "<DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{}\"/>",
            escape(&file.to_string_lossy())
        );
    }
    xml.push_str("</Collection>\n</VTKFile>\n");
    write_atomically(path, xml.as_bytes())
}

fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if let Some(parent) = path.parent() {
        fs::create_dir_all(parent)?;
    }
    let tmp = path.with_extension("tmp");
    {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.flush()?;
    }
    fs::rename(&tmp, path)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn push_f64_block(out: &mut String, values: &[f64]) {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    push_block(out, &bytes);
}

/// VTK "binary" inline format: base64 of (UInt64 byte count header ++ data).
fn push_block(out: &mut String, data: &[u8]) {
    let mut block = Vec::with_capacity(8 + data.len());
    block.extend_from_slice(&(data.len() as u64).to_le_bytes());
    block.extend_from_slice(data);
    base64_into(out, &block);
}

const BASE64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 with padding (RFC 4648 §4).
fn base64_into(out: &mut String, data: &[u8]) {
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        let sextets = [(v >> 18) & 63, (v >> 12) & 63, (v >> 6) & 63, v & 63];
        for (k, s) in sextets.iter().enumerate() {
            if k <= chunk.len() {
                out.push(BASE64[*s as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (input, expected) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foobar", "Zm9vYmFy"),
        ] {
            let mut s = String::new();
            base64_into(&mut s, input.as_bytes());
            assert_eq!(s, expected);
        }
    }

    #[test]
    fn vtu_has_one_vertex_per_particle_and_every_array() {
        let dir = tempfile::tempdir().unwrap();
        let frame = Frame {
            time: 1.5,
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            arrays: vec![FrameArray {
                name: "pressure".into(),
                components: 1,
                values: vec![1.0, 2.0],
            }],
        };
        let path = dir.path().join("f.vtu");
        write_vtu(&path, &frame).unwrap();
        let text = fs::read_to_string(&path).unwrap();
        assert!(text.contains("NumberOfPoints=\"2\" NumberOfCells=\"2\""));
        assert!(text.contains("Name=\"pressure\""));
        assert!(!dir.path().join("f.tmp").exists());
        let bad = Frame {
            arrays: vec![FrameArray {
                name: "v".into(),
                components: 3,
                values: vec![0.0],
            }],
            ..frame
        };
        assert!(write_vtu(&path, &bad).is_err());
    }
}
