//! Scenes carried by a link, so that a teacher shares a scene file as a
//! URL of the browser build (issue 33): `?scene=NAME` names a shipped
//! scene, `#scene=DATA` carries a scene file's own text, and `#lesson=DATA`
//! a lesson's.
//!
//! `DATA` is the file's UTF-8 text compressed with raw DEFLATE (RFC 1951,
//! no zlib or gzip header) and written in unpadded base64url (RFC 4648
//! §5), so a browser makes the same link with `CompressionStream
//! ("deflate-raw")`. The text is in the fragment (after `#`), which the
//! browser never sends to the server: the file reaches only the page.
//!
//! A link is untrusted input: its data is bounded ([`MAX_DATA`] characters,
//! [`MAX_TEXT`] bytes once inflated, so a small link cannot inflate into a
//! large text), and every way it can be malformed is a [`LinkError`] that
//! says what is wrong.

use std::fmt;

use base64::Engine as _;
use base64::alphabet::URL_SAFE;
use base64::engine::DecodePaddingMode;
use base64::engine::general_purpose::{GeneralPurpose, GeneralPurposeConfig, URL_SAFE_NO_PAD};

/// base64url as links are read: padded or not, and the last character's
/// spare bits ignored (as a browser's `atob` ignores them).
const LENIENT: GeneralPurpose = GeneralPurpose::new(
    &URL_SAFE,
    GeneralPurposeConfig::new()
        .with_decode_padding_mode(DecodePaddingMode::Indifferent)
        .with_decode_allow_trailing_bits(true),
);

/// Longest text a link may carry, bytes (inflated): a scene file is a few
/// kB, the largest shipped lesson 12 kB.
pub const MAX_TEXT: usize = 1 << 20;

/// Longest `DATA` a link may carry, characters: [`MAX_TEXT`] packs into
/// fewer (base64 of DEFLATE's worst case, about 1.4 Mi), and Chromium
/// drops a whole URL past 2 MiB, so a browser never hands the page more.
pub const MAX_DATA: usize = 2 << 20;

/// What a link's fragment carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A scene file (TOML), `#scene=`.
    Scene,
    /// A lesson file (Python), `#lesson=`.
    Lesson,
}

impl Kind {
    /// The fragment's key: `scene` or `lesson`.
    pub fn key(self) -> &'static str {
        match self {
            Kind::Scene => "scene",
            Kind::Lesson => "lesson",
        }
    }

    /// The kind of file a path names by its extension (`.py` is a lesson,
    /// anything else a scene).
    pub fn of_file(name: &str) -> Self {
        if name.to_ascii_lowercase().ends_with(".py") {
            Kind::Lesson
        } else {
            Kind::Scene
        }
    }
}

/// Why a link's data cannot be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinkError {
    /// More than [`MAX_DATA`] characters of data.
    TooLong(usize),
    /// Not base64url (a character outside `A–Z a–z 0–9 - _`, or a length
    /// no encoding has).
    NotBase64(String),
    /// Not raw DEFLATE data, or cut short.
    NotDeflate,
    /// Inflates past [`MAX_TEXT`] bytes.
    TooLarge,
    /// The inflated text is not UTF-8.
    NotUtf8,
}

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinkError::TooLong(n) => write!(
                f,
                "the link carries {n} characters of data, more than the {MAX_DATA} a link may carry"
            ),
            LinkError::NotBase64(why) => {
                write!(
                    f,
                    "the link's data is not base64url ({why}): was it cut short or changed?"
                )
            }
            LinkError::NotDeflate => write!(
                f,
                "the link's data is not a compressed file (raw DEFLATE): was it cut short or changed?"
            ),
            LinkError::TooLarge => write!(
                f,
                "the link's file is larger than the {} MiB a link may carry",
                MAX_TEXT >> 20
            ),
            LinkError::NotUtf8 => write!(f, "the link's file is not UTF-8 text"),
        }
    }
}

impl std::error::Error for LinkError {}

/// `text` as a link's `DATA`: raw DEFLATE at the best compression, in
/// unpadded base64url.
pub fn encode(text: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), 10);
    URL_SAFE_NO_PAD.encode(packed)
}

/// The text a link's `DATA` carries. Errors: see [`LinkError`].
pub fn decode(data: &str) -> Result<String, LinkError> {
    // A fragment copied by hand may keep a trailing newline.
    let data = data.trim();
    if data.len() > MAX_DATA {
        return Err(LinkError::TooLong(data.len()));
    }
    let packed = LENIENT
        .decode(data)
        .map_err(|e| LinkError::NotBase64(e.to_string()))?;
    let bytes = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_TEXT).map_err(
        |e| match e.status {
            miniz_oxide::inflate::TINFLStatus::HasMoreOutput => LinkError::TooLarge,
            _ => LinkError::NotDeflate,
        },
    )?;
    String::from_utf8(bytes).map_err(|_| LinkError::NotUtf8)
}

/// The file a link's fragment (`location.hash`, with or without its `#`)
/// carries: `None` when it carries nothing of ours (empty, an anchor, a
/// key other than `scene` or `lesson`, or an empty value), else the kind
/// and the text, or why it cannot be read.
pub fn from_fragment(fragment: &str) -> Option<Result<(Kind, String), LinkError>> {
    let fragment = fragment.strip_prefix('#').unwrap_or(fragment);
    let (key, data) = fragment.split_once('=')?;
    let kind = match key {
        "scene" => Kind::Scene,
        "lesson" => Kind::Lesson,
        _ => return None,
    };
    if data.trim().is_empty() {
        return None;
    }
    Some(decode(data).map(|text| (kind, text)))
}

/// Where the scene being played came from, so that a link can open it
/// again.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneSource {
    /// A shipped scene, by its file name ([`crate::assets::SCENES`]).
    Shipped(String),
    /// A file's text (dropped on the page, carried by a link, or read from
    /// disk), with the name it was opened under.
    Text {
        /// The file's name, for messages.
        name: String,
        /// Its text.
        text: String,
    },
}

/// The link that opens `source` in the browser build served at `base`
/// (the page's address without query or fragment, for instance
/// `http://localhost:8000/`).
pub fn link(base: &str, source: &SceneSource) -> String {
    match source {
        SceneSource::Shipped(name) => {
            let name = name.strip_suffix(".toml").unwrap_or(name);
            format!("{}?scene={name}", page(base))
        }
        SceneSource::Text { name, text } => file_link(base, name, text),
    }
}

/// The link that opens the file `name` with `text` (a scene, or a lesson
/// by its `.py`) in the browser build served at `base`.
pub fn file_link(base: &str, name: &str, text: &str) -> String {
    format!(
        "{}#{}={}",
        page(base),
        Kind::of_file(name).key(),
        encode(text)
    )
}

/// The link that opens the shipped lesson `name` (its file name,
/// [`crate::assets::LESSONS`]) in the browser build served at `base`.
pub fn shipped_lesson_link(base: &str, name: &str) -> String {
    let name = name.strip_suffix(".py").unwrap_or(name);
    format!("{}?lesson={name}", page(base))
}

/// `base` without its query or fragment.
fn page(base: &str) -> &str {
    base.split(['?', '#']).next().unwrap_or(base)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_scene_and_lesson_goes_through_a_link_unchanged() {
        for (name, text) in crate::assets::SCENES.iter().chain(crate::assets::LESSONS) {
            let link = file_link("http://localhost:8000/", name, text);
            let fragment = link.split_once('#').unwrap().1;
            let (kind, back) = from_fragment(fragment).unwrap().unwrap();
            assert_eq!(back, *text, "{name}");
            assert_eq!(kind, Kind::of_file(name));
            // Only URL-safe characters, and shorter than the text.
            assert!(
                fragment
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b"-_=".contains(&b))
            );
            assert!(
                fragment.len() < text.len(),
                "{name}: {} ≥ {}",
                fragment.len(),
                text.len()
            );
        }
    }

    /// Raw DEFLATE in base64url as others make it: "hello" compressed by
    /// Python's `zlib.compressobj(9, zlib.DEFLATED, -15)` (bytes
    /// `cb 48 cd c9 c9 07 00`). The browser test makes its links with
    /// Chromium's `CompressionStream("deflate-raw")`.
    #[test]
    fn a_browsers_raw_deflate_reads() {
        assert_eq!(decode("y0jNyckHAA").unwrap(), "hello");
    }

    #[test]
    fn a_bad_link_says_what_is_wrong() {
        assert_eq!(from_fragment(""), None);
        assert_eq!(from_fragment("#top"), None);
        // Not ours: another key, or no data (the page opens the default).
        assert_eq!(from_fragment("#picture=abc"), None);
        assert_eq!(from_fragment("#scene="), None);
        assert!(matches!(decode("y0jN*ckHAA"), Err(LinkError::NotBase64(_))));
        // Cut short (and padded, or with spare bits set, as browsers allow).
        assert_eq!(decode("y0jNyc"), Err(LinkError::NotDeflate));
        assert_eq!(decode("y0jNyckHAA=="), Ok("hello".into()));
        assert_eq!(decode("y0jNyckHAB"), Ok("hello".into()));
        // Not DEFLATE at all (block type 3 is reserved).
        assert_eq!(decode("____"), Err(LinkError::NotDeflate));
        // A bomb: 64 MiB of zeros is a small link, refused past MAX_TEXT.
        let bomb = URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec(
            &vec![b'0'; 64 << 20],
            10,
        ));
        assert!(bomb.len() < MAX_DATA);
        assert_eq!(decode(&bomb), Err(LinkError::TooLarge));
        let long = "A".repeat(MAX_DATA + 4);
        assert_eq!(decode(&long), Err(LinkError::TooLong(MAX_DATA + 4)));
        let not_utf8 =
            URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec(&[0xff, 0xfe], 6));
        assert_eq!(decode(&not_utf8), Err(LinkError::NotUtf8));
        for e in [
            LinkError::NotDeflate,
            LinkError::TooLarge,
            LinkError::TooLong(9),
        ] {
            assert!(e.to_string().starts_with("the link"), "{e}");
        }
    }

    #[test]
    fn a_shipped_scene_is_linked_by_name() {
        let shipped = SceneSource::Shipped("ten_pucks.toml".into());
        assert_eq!(
            link("http://x/lightcone/?scene=old#scene=abc", &shipped),
            "http://x/lightcone/?scene=ten_pucks"
        );
        let text = SceneSource::Text {
            name: "mine.toml".into(),
            text: "title = \"mine\"\n".into(),
        };
        let l = link("http://x/", &text);
        let (_, back) = from_fragment(l.split_once('#').unwrap().1)
            .unwrap()
            .unwrap();
        assert_eq!(back, "title = \"mine\"\n");
    }
}
