//! ART DTrack's ASCII UDP output: the 6d body records a CAVE's tracking PC
//! sends every frame, read as head poses.
//!
//! A DTrack2 packet is a few lines of ASCII separated by CR LF (or LF), one
//! record per line, each starting with its identifier. The ones used here
//! (DTrack2 manual, Technical Appendix B.2 "Output of measurement data via
//! Ethernet"):
//!
//! ```text
//! fr 21753                                      frame counter
//! ts 39596.024831                               timestamp, s since midnight (optional)
//! 6dcal 2                                       number of calibrated bodies (optional)
//! 6d 1 [0 1.000][326.848 -187.216 109.503 -160.4704 -3.6963 -7.0913][b0 b1 … b8]
//! ```
//!
//! A `6d` line gives the number of *tracked* bodies (an untracked body does
//! not appear), then per body three bracketed blocks: `[id quality]`,
//! `[sx sy sz η θ φ]` (position in **millimetres**, room coordinates, and
//! Euler angles in degrees, ignored here as the manual recommends) and
//! `[b0 … b8]`, the rotation matrix **column by column**:
//! `R = [[b0 b3 b6], [b1 b4 b7], [b2 b5 b8]]`. Every other record (`3d`,
//! `6df`, `6di`, `gl`, …) is skipped.
//!
//! Parsing treats the packet as untrusted: any malformed record is an error
//! that names the line, the field and what was there, and the packet is
//! dropped whole (a half-read pose is never published).

use glam::{DMat3, DQuat, DVec3};

/// Longest packet read, bytes (a DTrack packet is well under 10 kB; more is
/// not DTrack).
pub const MAX_PACKET: usize = 65_507;
/// Most bodies a `6d` record may give (DTrack2 tracks at most a few dozen
/// standard bodies; a larger count is not DTrack, and is refused before
/// anything is kept for it).
pub const MAX_BODIES: usize = 256;

/// One tracked 6DOF body of a packet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body6d {
    /// Body ID (from 0, as DTrack numbers them).
    pub id: u32,
    /// Quality value (DTrack2: unused for standard bodies, 1.000).
    pub quality: f64,
    /// Position, metres, room coordinates (converted from DTrack's mm).
    pub position: DVec3,
    /// Orientation, room from body.
    pub rotation: DMat3,
}

/// What one packet says.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Packet {
    /// `fr`: DTrack's frame counter.
    pub frame: Option<u64>,
    /// `ts`: timestamp, seconds since midnight (UTC per DTrack's clock).
    pub timestamp: Option<f64>,
    /// `6d`: every tracked standard body.
    pub bodies: Vec<Body6d>,
}

/// Why a packet was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line} ({record}): {message}")]
pub struct PacketError {
    /// 1-based line in the packet.
    pub line: usize,
    /// The record identifier (`fr`, `6d`, …), or `packet`.
    pub record: String,
    /// What is wrong, naming the field.
    pub message: String,
}

fn error(line: usize, record: &str, message: impl Into<String>) -> PacketError {
    PacketError {
        line,
        record: record.to_owned(),
        message: message.into(),
    }
}

/// The packet's bytes shown safely in a message: printable ASCII kept,
/// everything else escaped, at most `max` characters.
#[must_use]
pub fn show_content(bytes: &[u8], max: usize) -> String {
    let mut out = String::new();
    for &b in bytes.iter().take(max) {
        match b {
            b'\r' => out.push_str("\\r"),
            b'\n' => out.push_str("\\n"),
            0x20..=0x7e => out.push(b as char),
            _ => out.push_str(&format!("\\x{b:02x}")),
        }
    }
    if bytes.len() > max {
        out.push_str(&format!("… ({} bytes)", bytes.len()));
    }
    out
}

fn number<T: std::str::FromStr>(
    line: usize,
    record: &str,
    field: &str,
    text: &str,
) -> Result<T, PacketError> {
    text.parse()
        .map_err(|_| error(line, record, format!("{field}: `{text}` is not a number")))
}

fn finite(line: usize, record: &str, field: &str, text: &str) -> Result<f64, PacketError> {
    let v: f64 = number(line, record, field, text)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(error(
            line,
            record,
            format!("{field}: `{text}` is not finite"),
        ))
    }
}

/// Parses one DTrack ASCII packet.
///
/// # Errors
/// [`PacketError`] naming the line, record and field of the first problem:
/// not ASCII text, a number that does not parse or is not finite, a
/// missing or extra bracket block, a body count that disagrees with the
/// blocks, a rotation matrix that is not a rotation (orthonormal to 1e-3,
/// determinant +1), a position beyond ±1 km, more than [`MAX_BODIES`]
/// bodies, no `fr` line (DTrack sends one in every packet).
pub fn parse(bytes: &[u8]) -> Result<Packet, PacketError> {
    let text =
        std::str::from_utf8(bytes).map_err(|e| error(0, "packet", format!("not text: {e}")))?;
    if !text.is_ascii() {
        return Err(error(0, "packet", "not ASCII"));
    }
    let mut packet = Packet::default();
    let mut any = false;
    for (k, raw) in text.split('\n').enumerate() {
        let line = k + 1;
        let raw = raw.trim_end_matches('\r').trim();
        if raw.is_empty() {
            continue;
        }
        let (record, rest) = raw.split_once(' ').unwrap_or((raw, ""));
        let rest = rest.trim();
        match record {
            "fr" => {
                packet.frame = Some(number(line, record, "frame counter", rest)?);
                any = true;
            }
            "ts" => {
                packet.timestamp = Some(finite(line, record, "timestamp", rest)?);
                any = true;
            }
            "6d" => {
                packet.bodies = parse_6d(line, rest)?;
                any = true;
            }
            r if r.chars().all(|c| c.is_ascii_alphanumeric()) && !r.is_empty() => {
                // Another record kind (3d, 6df, 6dcal, gl, …): not ours.
                any = true;
            }
            _ => {
                return Err(error(
                    line,
                    "packet",
                    format!(
                        "`{}` is not a DTrack record identifier",
                        show_content(record.as_bytes(), 20)
                    ),
                ));
            }
        }
    }
    if !any {
        return Err(error(0, "packet", "empty"));
    }
    if packet.frame.is_none() {
        return Err(error(
            1,
            "packet",
            "no frame counter (`fr` line): not a DTrack packet",
        ));
    }
    Ok(packet)
}

/// The bracket blocks of a record: `[a b][c d]` → `["a b", "c d"]`.
fn blocks(line: usize, record: &str, text: &str) -> Result<Vec<String>, PacketError> {
    let mut out = Vec::new();
    let mut rest = text.trim();
    while !rest.is_empty() {
        let Some(after_open) = rest.strip_prefix('[') else {
            return Err(error(
                line,
                record,
                format!(
                    "expected `[`, found `{}`",
                    show_content(rest.as_bytes(), 20)
                ),
            ));
        };
        let close = after_open
            .find(']')
            .ok_or_else(|| error(line, record, "a `[` block is not closed"))?;
        out.push(after_open[..close].trim().to_owned());
        rest = after_open[close + 1..].trim_start();
    }
    Ok(out)
}

fn parse_6d(line: usize, rest: &str) -> Result<Vec<Body6d>, PacketError> {
    let record = "6d";
    let (count, rest) = rest.split_once(' ').unwrap_or((rest, ""));
    let count: usize = number(line, record, "number of bodies", count)?;
    if count > MAX_BODIES {
        return Err(error(
            line,
            record,
            format!("number of bodies: {count} is more than {MAX_BODIES}"),
        ));
    }
    let blocks = blocks(line, record, rest)?;
    if blocks.len() != 3 * count {
        return Err(error(
            line,
            record,
            format!(
                "{count} bodies need {} bracket blocks, found {}",
                3 * count,
                blocks.len()
            ),
        ));
    }
    let mut bodies = Vec::with_capacity(count);
    for (b, chunk) in blocks.chunks(3).enumerate() {
        let head: Vec<&str> = chunk[0].split_whitespace().collect();
        let pose: Vec<&str> = chunk[1].split_whitespace().collect();
        let matrix: Vec<&str> = chunk[2].split_whitespace().collect();
        let field = |name: &str| format!("body {b} {name}");
        if head.len() != 2 {
            return Err(error(
                line,
                record,
                format!(
                    "{}: expected [id quality], found [{}]",
                    field("header"),
                    chunk[0]
                ),
            ));
        }
        if pose.len() != 6 {
            return Err(error(
                line,
                record,
                format!(
                    "{}: expected [sx sy sz η θ φ], found {} numbers",
                    field("position"),
                    pose.len()
                ),
            ));
        }
        if matrix.len() != 9 {
            return Err(error(
                line,
                record,
                format!(
                    "{}: expected [b0 … b8], found {} numbers",
                    field("rotation"),
                    matrix.len()
                ),
            ));
        }
        let id: u32 = number(line, record, &field("id"), head[0])?;
        let quality = finite(line, record, &field("quality"), head[1])?;
        let mut s = [0.0; 3];
        for (i, t) in pose[..3].iter().enumerate() {
            s[i] = finite(line, record, &field(&format!("s{}", ["x", "y", "z"][i])), t)?;
        }
        for (i, t) in pose[3..].iter().enumerate() {
            finite(line, record, &field(["η", "θ", "φ"][i]), t)?;
        }
        let mut m = [0.0; 9];
        for (i, t) in matrix.iter().enumerate() {
            m[i] = finite(line, record, &field(&format!("b{i}")), t)?;
        }
        // Column by column: b0 b1 b2 is the first column.
        let rotation = DMat3::from_cols_array(&m);
        let orthonormal = (rotation.transpose() * rotation - DMat3::IDENTITY)
            .to_cols_array()
            .iter()
            .all(|e| e.abs() < 1e-3);
        if !orthonormal || rotation.determinant() < 0.0 {
            return Err(error(
                line,
                record,
                format!("{}: b0 … b8 is not a rotation matrix", field("rotation")),
            ));
        }
        let position = crate::report::check_position(DVec3::from_array(s) / 1000.0)
            .map_err(|e| error(line, record, format!("{}: {e}", field("position"))))?;
        bodies.push(Body6d {
            id,
            quality,
            position,
            rotation,
        });
    }
    Ok(bodies)
}

/// The unit quaternion of a rotation matrix (assumed orthonormal, as
/// [`parse`] checks), normalised.
#[must_use]
pub fn quaternion(rotation: DMat3) -> DQuat {
    DQuat::from_mat3(&rotation).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The manual's own example line (DTrack2, B.2.3).
    const MANUAL: &str = "fr 21753\r\nts 39596.024831\r\n6dcal 1\r\n6d 1 [0 1.000][326.848 -187.216 109.503 -160.4704 -3.6963 -7.0913][-0.940508 -0.339238 -0.019025 0.333599 -0.932599 0.137735 -0.064467 0.123194 0.990286]\r\n";

    #[test]
    fn reads_the_manual_example() {
        let p = parse(MANUAL.as_bytes()).unwrap();
        assert_eq!(p.frame, Some(21753));
        assert_eq!(p.timestamp, Some(39596.024831));
        assert_eq!(p.bodies.len(), 1);
        let b = p.bodies[0];
        assert_eq!(b.id, 0);
        assert!((b.position - DVec3::new(0.326848, -0.187216, 0.109503)).length() < 1e-12);
        // Column by column: the first column is (b0, b1, b2).
        assert_eq!(
            b.rotation.x_axis,
            DVec3::new(-0.940508, -0.339238, -0.019025)
        );
        // The angles are not used (the manual recommends the matrix).
        let q = quaternion(b.rotation);
        let back = DMat3::from_quat(q);
        assert!((back.x_axis - b.rotation.x_axis).length() < 1e-5);
    }

    #[test]
    fn malformed_packets_name_line_and_field() {
        let cases: &[(&[u8], &str)] = &[
            (b"", "empty"),
            (b"\xff\xfe", "not text"),
            (b"fr abc\n", "frame counter: `abc`"),
            (b"6d 1 [0 1.0][1 2 3 0 0 0]\n", "need 3 bracket blocks"),
            (
                b"6d 1 [0 1.0][1 2 nan 0 0 0][1 0 0 0 1 0 0 0 1]\n",
                "body 0 sz: `nan` is not finite",
            ),
            (
                b"6d 1 [0 1.0][1 2 3 0 0 0][2 0 0 0 1 0 0 0 1]\n",
                "not a rotation",
            ),
            (
                b"6d 1 [0 1.0][1 2 3 0 0 0][-1 0 0 0 1 0 0 0 1]\n",
                "not a rotation",
            ),
            (
                b"6d 1 [0 1.0][1 2 3 0 0 0][1 0 0 0 1 0 0 0 1\n",
                "not closed",
            ),
            (
                b"6d 1 [0 1.0][1e9 2 3 0 0 0][1 0 0 0 1 0 0 0 1]\n",
                "beyond",
            ),
            (b"fr 1\n<html>\n", "line 2"),
            (
                b"fr 1\n6d 6148914691236517206 [0 1][0 0 0 0 0 0]\n",
                "6148914691236517206 is more than 256",
            ),
            (
                b"6d 1 [0 1.0][1e300 2 3 0 0 0][1 0 0 0 1 0 0 0 1]\n",
                "beyond",
            ),
            (b"6d 0\n", "no frame counter"),
        ];
        for (bytes, want) in cases {
            let e = parse(bytes).unwrap_err().to_string();
            assert!(e.contains(want), "{:?}: {e}", show_content(bytes, 80));
        }
    }

    #[test]
    fn no_tracked_body_and_other_records() {
        let p = parse(b"fr 7\n6dcal 2\n6d 0\n3d 0\n").unwrap();
        assert!(parse(b"GET / HTTP/1.1\r\n\r\n").is_err());
        assert_eq!(p.frame, Some(7));
        assert!(p.bodies.is_empty());
    }

    #[test]
    fn content_is_shown_escaped_and_capped() {
        assert_eq!(show_content(b"a\r\n\x00", 10), "a\\r\\n\\x00");
        assert!(show_content(&[b'x'; 50], 10).ends_with("(50 bytes)"));
    }
}
