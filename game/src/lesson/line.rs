//! The lesson channel's framing, both ways: one JSON message a line, each
//! line bounded, so that neither process can grow the other's memory by
//! writing without a newline.

use std::io::{BufRead, Read};

pub use lightcone_lesson::protocol::MAX_LINE;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reader_refuses_overlong_lines_and_reads_the_rest() {
        let mut ok = std::io::Cursor::new(b"{\"a\":1}\nlast".to_vec());
        assert_eq!(read_line(&mut ok).unwrap().unwrap(), b"{\"a\":1}");
        assert_eq!(read_line(&mut ok).unwrap().unwrap(), b"last");
        assert!(read_line(&mut ok).unwrap().is_none());
        let mut long = std::io::Cursor::new(vec![b'x'; MAX_LINE + 10]);
        let err = read_line(&mut long).unwrap_err();
        assert!(err.contains("longer than 16 MiB"), "{err}");
    }
}
