//! The lesson channel's framing, both ways: one JSON message a line, each
//! line bounded, so that neither process can grow the other's memory by
//! writing without a newline.

use std::io::BufRead;

/// Longest line either process accepts from the other, bytes.
pub const MAX_LINE: usize = 16 << 20;

/// Reads one line of at most [`MAX_LINE`] bytes (without its newline).
/// `Ok(None)` at the end of the stream.
pub(crate) fn read_line(reader: &mut impl BufRead) -> Result<Option<Vec<u8>>, String> {
    let mut line = Vec::new();
    let n = reader
        .by_ref()
        .take(MAX_LINE as u64 + 1)
        .read_until(b'\n', &mut line)
        .map_err(|e| format!("cannot read the lesson's process: {e}"))?;
    if n == 0 {
        return Ok(None);
    }
    if line.last() == Some(&b'\n') {
        line.pop();
    } else if line.len() > MAX_LINE {
        return Err(format!("it sent a line longer than {} MiB", MAX_LINE >> 20));
    }
    Ok(Some(line))
}
