//! VRPN's tracker stream, read over TCP: the head poses a VRPN server
//! (`vrpn_server`, OptiTrack Motive, Vicon Tracker, ART's VRPN output, …)
//! sends for one tracker device, as VRPN's own `tcp://` clients read them.
//!
//! The wire format (VRPN 07.xx, `vrpn_Connection.C` and `vrpn_Tracker.C`;
//! every number big-endian, "network order"):
//!
//! - **Cookie.** Right after the TCP connection each side sends 24 bytes:
//!   `vrpn: ver. 07.35  0` (the version, two spaces, the log mode as a
//!   digit), padded with NULs. The major version (07) must match.
//! - **Messages.** A 24-byte header: five `i32` — the message's length
//!   *including* the header and *without* padding, the time (seconds,
//!   microseconds), the sender id, the message type id — then 4 bytes of
//!   padding (a sequence number in recent servers, ignored). The payload
//!   follows, padded with NULs to a multiple of 8 bytes.
//! - **Names.** Sender and type ids are the server's own: it describes each
//!   one once, in a message of type −1 (a sender: `Head`, `Tracker0`) or −2
//!   (a type: `vrpn_Tracker Pos_Quat`) whose *sender* field holds the id
//!   described and whose payload is an `i32` length and the name with its
//!   terminating NUL. Type −5 (disconnect, written to VRPN's log files) is
//!   taken as the end of the stream should a server send it; −3 (UDP
//!   description) and −4 (log description) are skipped, as is every
//!   message of another type.
//! - **Poses.** A `vrpn_Tracker Pos_Quat` payload (64 bytes): the sensor
//!   (`i32`), 4 bytes of padding, the position (3 × `f64`, metres, the
//!   tracker's room frame) and the orientation as a quaternion
//!   (4 × `f64`, `x y z w`).
//!
//! A client that announces no UDP port gets every message over TCP, so
//! this client announces none. Everything read is untrusted: a header whose
//! length is impossible ends the connection (its framing is lost), a pose
//! that is not finite, lies beyond ±1 km ([`crate::report`]) or whose
//! quaternion has no length is refused alone, as is a description whose
//! name is longer than [`MAX_NAME_LEN`]; each error names the field and
//! shows what was there. At most [`MAX_NAMES`] sender and type names are
//! kept, the oldest forgotten first, so a server cannot grow the client.

use glam::{DQuat, DVec3};

/// The port a VRPN server listens on unless told otherwise.
pub const DEFAULT_PORT: u16 = 3883;
/// Length of the cookie each side sends first, bytes.
pub const COOKIE_LEN: usize = 24;
/// The protocol's major version (07): the server's must be the same.
pub const MAJOR_VERSION: u32 = 7;
/// Length of a message header, bytes (20 bytes padded to 8).
pub const HEADER_LEN: usize = 24;
/// Longest payload accepted, bytes (a tracker's are 64; a name is short).
pub const MAX_PAYLOAD: usize = 1 << 16;
/// Longest sender or type name kept, bytes (VRPN's own names are at most
/// 100, `vrpn_Shared.h`'s `cName`); a longer description is refused alone.
pub const MAX_NAME_LEN: usize = 255;
/// Most sender names, and most type names, kept at once (VRPN's own
/// limits, `vrpn_CONNECTION_MAX_SENDERS` and `_TYPES`): a server that
/// describes more has its oldest descriptions forgotten first.
pub const MAX_NAMES: usize = 2000;
/// The type name of a tracker's position-and-orientation report.
pub const POS_QUAT: &str = "vrpn_Tracker Pos_Quat";

/// Message type: a sender's name (its id in the sender field).
pub const SENDER_DESCRIPTION: i32 = -1;
/// Message type: a type's name (its id in the sender field).
pub const TYPE_DESCRIPTION: i32 = -2;
/// Message type: the server closes the connection.
pub const DISCONNECT: i32 = -5;

const ALIGN: usize = 8;
const MAGIC: &[u8] = b"vrpn: ver. 07.35";

/// Which device to follow: `NAME@HOST[:PORT]`, as VRPN names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Device {
    /// The tracker's name on the server (`Head`, `Tracker0`, a rigid body).
    pub name: String,
    /// Host name or address of the server.
    pub host: String,
    /// Its TCP port.
    pub port: u16,
}

impl Device {
    /// Reads `NAME@HOST[:PORT]` (the port defaults to [`DEFAULT_PORT`]; an
    /// IPv6 host is written in brackets, `Head@[::1]:3883`).
    pub fn parse(text: &str) -> Result<Self, String> {
        let (name, server) = text
            .split_once('@')
            .ok_or_else(|| format!("`{text}` is not NAME@HOST[:PORT] (no `@`)"))?;
        if name.is_empty() || name.len() > 255 || name.contains('\0') {
            return Err(format!(
                "`{text}`: the device name must be 1 to 255 characters"
            ));
        }
        let (host, port) = if let Some(rest) = server.strip_prefix('[') {
            let (host, after) = rest
                .split_once(']')
                .ok_or_else(|| format!("`{text}`: `[` without `]` around the host"))?;
            match after.strip_prefix(':') {
                Some(p) => (host, Some(p)),
                None if after.is_empty() => (host, None),
                None => return Err(format!("`{text}`: `{after}` after the host")),
            }
        } else {
            match server.rsplit_once(':') {
                Some((h, _)) if h.contains(':') => {
                    return Err(format!(
                        "`{text}`: write an IPv6 host in brackets, NAME@[HOST]:PORT"
                    ));
                }
                Some((h, p)) => (h, Some(p)),
                None => (server, None),
            }
        };
        if host.is_empty() {
            return Err(format!("`{text}`: no host after `@`"));
        }
        let port = match port {
            Some(p) => p
                .parse::<u16>()
                .ok()
                .filter(|p| *p > 0)
                .ok_or_else(|| format!("`{text}`: `{p}` is not a port (1 to 65535)"))?,
            None => DEFAULT_PORT,
        };
        Ok(Self {
            name: name.to_owned(),
            host: host.to_owned(),
            port,
        })
    }
}

impl std::fmt::Display for Device {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.host.contains(':') {
            write!(f, "{}@[{}]:{}", self.name, self.host, self.port)
        } else {
            write!(f, "{}@{}:{}", self.name, self.host, self.port)
        }
    }
}

/// Why something read from a VRPN server was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field}: {message}; content: \"{content}\"")]
pub struct ProtocolError {
    /// What was being read (`cookie`, `header.length`, `Pos_Quat.position`, …).
    pub field: String,
    /// What is wrong.
    pub message: String,
    /// The bytes concerned, shown safely (at most 120 characters).
    pub content: String,
}

fn error(field: &str, message: impl Into<String>, bytes: &[u8]) -> ProtocolError {
    ProtocolError {
        field: field.to_owned(),
        message: message.into(),
        content: crate::dtrack::show_content(bytes, 120),
    }
}

/// The cookie this client sends: `MAGIC`, two spaces, log mode 0, NULs.
#[must_use]
pub fn cookie() -> [u8; COOKIE_LEN] {
    let mut c = [0u8; COOKIE_LEN];
    c[..MAGIC.len()].copy_from_slice(MAGIC);
    c[MAGIC.len()..MAGIC.len() + 3].copy_from_slice(b"  0");
    c
}

/// Checks the server's cookie; its `(major, minor)` version.
pub fn check_cookie(bytes: &[u8]) -> Result<(u32, u32), ProtocolError> {
    let prefix = b"vrpn: ver. ";
    if bytes.len() < COOKIE_LEN || !bytes.starts_with(prefix) {
        return Err(error("cookie", "not a VRPN server", bytes));
    }
    let version = std::str::from_utf8(&bytes[prefix.len()..prefix.len() + 5])
        .ok()
        .and_then(|v| v.split_once('.'))
        .and_then(|(a, b)| Some((a.parse::<u32>().ok()?, b.parse::<u32>().ok()?)));
    match version {
        Some((major, minor)) if major == MAJOR_VERSION => Ok((major, minor)),
        Some((major, _)) => Err(error(
            "cookie",
            format!("protocol version {major:02}, this client speaks {MAJOR_VERSION:02}"),
            bytes,
        )),
        None => Err(error("cookie", "no version number", bytes)),
    }
}

/// A message header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// Payload length, bytes, without padding.
    pub payload_len: usize,
    /// Time the server stamped, seconds and microseconds.
    pub time: (i32, i32),
    /// Sender id (for a description: the id described).
    pub sender: i32,
    /// Message type id.
    pub kind: i32,
}

impl Header {
    /// Bytes the payload takes on the wire, with its padding.
    #[must_use]
    pub fn padded_len(&self) -> usize {
        self.payload_len.div_ceil(ALIGN) * ALIGN
    }
}

fn be_i32(bytes: &[u8], at: usize) -> i32 {
    let mut b = [0u8; 4];
    b.copy_from_slice(&bytes[at..at + 4]);
    i32::from_be_bytes(b)
}

fn be_f64(bytes: &[u8], at: usize) -> f64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[at..at + 8]);
    f64::from_be_bytes(b)
}

/// Reads a header (the first [`HEADER_LEN`] bytes of `bytes`).
pub fn parse_header(bytes: &[u8]) -> Result<Header, ProtocolError> {
    if bytes.len() < HEADER_LEN {
        return Err(error("header", "shorter than 24 bytes", bytes));
    }
    let total = be_i32(bytes, 0);
    let payload_len = usize::try_from(total)
        .ok()
        .and_then(|t| t.checked_sub(HEADER_LEN))
        .filter(|n| *n <= MAX_PAYLOAD)
        .ok_or_else(|| {
            error(
                "header.length",
                format!("{total} is not 24 to {} bytes", HEADER_LEN + MAX_PAYLOAD),
                &bytes[..HEADER_LEN],
            )
        })?;
    Ok(Header {
        payload_len,
        time: (be_i32(bytes, 4), be_i32(bytes, 8)),
        sender: be_i32(bytes, 12),
        kind: be_i32(bytes, 16),
    })
}

/// A sender's or type's name from a description's payload.
pub fn parse_name(payload: &[u8]) -> Result<String, ProtocolError> {
    if payload.len() < 4 {
        return Err(error("description", "no name length", payload));
    }
    let n = be_i32(payload, 0);
    let name = usize::try_from(n)
        .ok()
        .filter(|n| (1..=payload.len() - 4).contains(n))
        .map(|n| &payload[4..4 + n])
        .ok_or_else(|| error("description.length", format!("{n} does not fit"), payload))?;
    let name = name.strip_suffix(b"\0").unwrap_or(name);
    if name.len() > MAX_NAME_LEN {
        return Err(error(
            "description.name",
            format!("{} bytes, longer than {MAX_NAME_LEN}", name.len()),
            payload,
        ));
    }
    std::str::from_utf8(name)
        .map(str::to_owned)
        .map_err(|_| error("description.name", "not UTF-8", payload))
}

/// One tracker report.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PosQuat {
    /// The sensor of the device (a device may track several).
    pub sensor: i32,
    /// Position, metres, the tracker's room frame.
    pub position: DVec3,
    /// Orientation, room from sensor, normalised.
    pub orientation: DQuat,
}

/// Reads a `vrpn_Tracker Pos_Quat` payload.
pub fn parse_pos_quat(payload: &[u8]) -> Result<PosQuat, ProtocolError> {
    if payload.len() < 64 {
        return Err(error(
            "Pos_Quat",
            format!("{} bytes, a report has 64", payload.len()),
            payload,
        ));
    }
    let v: Vec<f64> = (0..7).map(|i| be_f64(payload, 8 + 8 * i)).collect();
    let position = crate::report::check_position(DVec3::new(v[0], v[1], v[2]))
        .map_err(|e| error("Pos_Quat.position", e, &payload[..64]))?;
    let orientation = crate::report::unit_quaternion(DQuat::from_xyzw(v[3], v[4], v[5], v[6]))
        .map_err(|e| error("Pos_Quat.quaternion", e, &payload[..64]))?;
    Ok(PosQuat {
        sensor: be_i32(payload, 0),
        position,
        orientation,
    })
}

/// What the stream gave.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// A report from sender `sender` (its name, as described).
    Pose {
        /// The sender's name (`?id` if it was never described).
        sender: String,
        /// The report.
        pose: PosQuat,
    },
    /// A report refused alone (the stream goes on).
    Refused(ProtocolError),
    /// The server said it disconnects.
    Disconnect,
}

/// Splits the bytes a server sent into messages, keeping the names it
/// described. Feed it what arrives ([`Stream::push`]), take the events
/// ([`Stream::next_event`]).
#[derive(Debug, Default)]
pub struct Stream {
    buffer: Vec<u8>,
    /// Where the next message starts in `buffer` (what is before it is
    /// read; dropped at the next push).
    start: usize,
    senders: Names,
    types: Names,
    /// The device followed ([`Stream::following`]): its sender name is
    /// never forgotten.
    device: Option<String>,
}

/// The names a server described, by id: at most [`MAX_NAMES`], the
/// oldest description forgotten first, except the one `pinned` name.
#[derive(Debug, Default)]
struct Names {
    by_id: std::collections::HashMap<i32, String>,
    /// Ids from the oldest description to the newest.
    order: std::collections::VecDeque<i32>,
}

impl Names {
    fn insert(&mut self, id: i32, name: String, pinned: Option<&str>) {
        if self.by_id.insert(id, name).is_some() {
            self.order.retain(|i| *i != id);
        }
        self.order.push_back(id);
        while self.order.len() > MAX_NAMES {
            let Some(oldest) = self.order.pop_front() else {
                break;
            };
            if pinned.is_some() && self.by_id.get(&oldest).map(String::as_str) == pinned {
                // Kept, as if described last.
                self.order.push_back(oldest);
                continue;
            }
            self.by_id.remove(&oldest);
        }
    }

    fn get(&self, id: &i32) -> Option<&String> {
        self.by_id.get(id)
    }
}

impl Stream {
    /// A stream whose sender `device` (the tracker followed) is never
    /// forgotten, however many other senders the server describes after it
    /// (as the `Pos_Quat` type's name is not).
    #[must_use]
    pub fn following(device: &str) -> Self {
        Self {
            device: Some(device.to_owned()),
            ..Self::default()
        }
    }

    /// How many sender and type names are kept (each at most
    /// [`MAX_NAMES`]).
    #[must_use]
    pub fn names_kept(&self) -> (usize, usize) {
        (self.senders.by_id.len(), self.types.by_id.len())
    }

    /// Appends bytes read from the connection (after the cookie).
    pub fn push(&mut self, bytes: &[u8]) {
        self.buffer.drain(..self.start);
        self.start = 0;
        self.buffer.extend_from_slice(bytes);
    }

    /// The next event in what was pushed; `Ok(None)` until a whole message
    /// is there. An error means the framing is lost: drop the connection.
    pub fn next_event(&mut self) -> Result<Option<Event>, ProtocolError> {
        loop {
            let rest = &self.buffer[self.start..];
            if rest.len() < HEADER_LEN {
                return Ok(None);
            }
            let header = parse_header(rest)?;
            let end = HEADER_LEN + header.padded_len();
            if rest.len() < end {
                return Ok(None);
            }
            let payload = rest[HEADER_LEN..HEADER_LEN + header.payload_len].to_vec();
            self.start += end;
            match header.kind {
                SENDER_DESCRIPTION | TYPE_DESCRIPTION => {
                    // A description that does not parse is refused alone:
                    // its length was in the header, so the framing holds.
                    let name = match parse_name(&payload) {
                        Ok(name) => name,
                        Err(e) => return Ok(Some(Event::Refused(e))),
                    };
                    if header.kind == SENDER_DESCRIPTION {
                        self.senders
                            .insert(header.sender, name, self.device.as_deref());
                    } else {
                        self.types.insert(header.sender, name, Some(POS_QUAT));
                    }
                }
                DISCONNECT => return Ok(Some(Event::Disconnect)),
                kind if self.types.get(&kind).is_some_and(|t| t == POS_QUAT) => {
                    let sender = self
                        .senders
                        .get(&header.sender)
                        .cloned()
                        .unwrap_or_else(|| format!("?{}", header.sender));
                    return Ok(Some(match parse_pos_quat(&payload) {
                        Ok(pose) => Event::Pose { sender, pose },
                        Err(e) => Event::Refused(e),
                    }));
                }
                _ => {} // another device's or the connection's own
            }
        }
    }
}

/// One message as a server writes it (for tests and recorded streams).
#[must_use]
pub fn encode(sender: i32, kind: i32, time: (i32, i32), payload: &[u8]) -> Vec<u8> {
    let total = i32::try_from(HEADER_LEN + payload.len()).unwrap_or(i32::MAX);
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len() + ALIGN);
    for v in [total, time.0, time.1, sender, kind, 0] {
        out.extend_from_slice(&v.to_be_bytes());
    }
    out.extend_from_slice(payload);
    out.resize(out.len().div_ceil(ALIGN) * ALIGN, 0);
    out
}

/// A sender (`kind` [`SENDER_DESCRIPTION`]) or type
/// ([`TYPE_DESCRIPTION`]) description of `id` as `name`.
#[must_use]
pub fn encode_description(kind: i32, id: i32, name: &str) -> Vec<u8> {
    let mut payload = Vec::with_capacity(name.len() + 5);
    let n = i32::try_from(name.len() + 1).unwrap_or(i32::MAX);
    payload.extend_from_slice(&n.to_be_bytes());
    payload.extend_from_slice(name.as_bytes());
    payload.push(0);
    encode(id, kind, (0, 0), &payload)
}

/// A `Pos_Quat` payload.
#[must_use]
pub fn encode_pos_quat(sensor: i32, position: DVec3, orientation: DQuat) -> Vec<u8> {
    let mut p = Vec::with_capacity(64);
    p.extend_from_slice(&sensor.to_be_bytes());
    p.extend_from_slice(&[0; 4]);
    for v in position
        .to_array()
        .into_iter()
        .chain(orientation.to_array())
    {
        p.extend_from_slice(&v.to_be_bytes());
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cookie_is_vrpns_and_is_checked() {
        let c = cookie();
        assert_eq!(&c[..19], b"vrpn: ver. 07.35  0");
        assert!(c[19..].iter().all(|b| *b == 0));
        assert_eq!(check_cookie(&c), Ok((7, 35)));
        let mut old = c;
        old[11..16].copy_from_slice(b"04.11");
        let e = check_cookie(&old).unwrap_err();
        assert!(e.to_string().contains("version 04"), "{e}");
        let e = check_cookie(b"HTTP/1.1 400 Bad Request\r\n").unwrap_err();
        assert!(e.to_string().contains("not a VRPN server"), "{e}");
        assert!(e.to_string().contains("HTTP/1.1"), "{e}");
    }

    #[test]
    fn device_names_parse_and_bad_ones_say_why() {
        assert_eq!(
            Device::parse("Head@tracking-pc").unwrap(),
            Device {
                name: "Head".into(),
                host: "tracking-pc".into(),
                port: 3883
            }
        );
        let d = Device::parse("Tracker0@127.0.0.1:3999").unwrap();
        assert_eq!((d.host.as_str(), d.port), ("127.0.0.1", 3999));
        let d = Device::parse("Head@[::1]:4000").unwrap();
        assert_eq!((d.host.as_str(), d.port), ("::1", 4000));
        assert_eq!(d.to_string(), "Head@[::1]:4000");
        for (bad, says) in [
            ("Head", "no `@`"),
            ("@host", "device name"),
            ("Head@", "no host"),
            ("Head@host:0", "not a port"),
            ("Head@host:http", "not a port"),
            ("Head@[::1", "without `]`"),
            ("Head@fe80::1", "in brackets"),
        ] {
            let e = Device::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn a_stream_of_messages_gives_the_named_poses_in_order() {
        let q = DQuat::from_rotation_y(0.3);
        let mut bytes = Vec::new();
        bytes.extend(encode_description(SENDER_DESCRIPTION, 0, "Head"));
        bytes.extend(encode_description(TYPE_DESCRIPTION, 4, POS_QUAT));
        bytes.extend(encode_description(
            TYPE_DESCRIPTION,
            5,
            "vrpn_Tracker Velocity",
        ));
        bytes.extend(encode(
            0,
            4,
            (10, 5),
            &encode_pos_quat(0, DVec3::new(1.0, 1.7, -0.5), q),
        ));
        bytes.extend(encode(0, 5, (10, 6), &[0; 48])); // a velocity: skipped
        bytes.extend(encode(7, 4, (10, 7), &encode_pos_quat(2, DVec3::ZERO, q)));
        let mut s = Stream::default();
        // Byte by byte: a message is taken only once it is whole.
        let mut events = Vec::new();
        for b in &bytes {
            s.push(std::slice::from_ref(b));
            while let Some(e) = s.next_event().unwrap() {
                events.push(e);
            }
        }
        assert_eq!(events.len(), 2, "{events:?}");
        match &events[0] {
            Event::Pose { sender, pose } => {
                assert_eq!(sender, "Head");
                assert_eq!(pose.sensor, 0);
                assert_eq!(pose.position, DVec3::new(1.0, 1.7, -0.5));
                assert!(pose.orientation.dot(q).abs() > 1.0 - 1e-15);
            }
            e => panic!("{e:?}"),
        }
        assert!(
            matches!(&events[1], Event::Pose { sender, pose } if sender == "?7" && pose.sensor == 2)
        );
    }

    /// Bytes written by hand from VRPN's source, not by [`encode`]: the
    /// `VRPN Control` sender a server describes first (id 0), a type
    /// description (id 2), and one report (sender 0, type 2, at
    /// 1.5 s, sensor 3, position (1, 2, 3), quaternion (0, 0, 0, 1)).
    #[test]
    fn hand_written_vrpn_bytes_read_as_vrpn_means_them() {
        let mut b: Vec<u8> = Vec::new();
        // Header: length 24 + 17 ("VRPN Control" is 12 + NUL = 13, after its
        // 4-byte length), time 0, sender 0 (described), type -1; padding.
        b.extend([0, 0, 0, 41, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        b.extend([0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0]);
        b.extend([0, 0, 0, 13]);
        b.extend(b"VRPN Control\0");
        b.extend([0; 7]); // 17 padded to 24
        // Type 2 is "vrpn_Tracker Pos_Quat" (21 + NUL = 22; 26 → 32).
        b.extend([0, 0, 0, 50, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2]);
        b.extend([0xff, 0xff, 0xff, 0xfe, 0, 0, 0, 0]);
        b.extend([0, 0, 0, 22]);
        b.extend(b"vrpn_Tracker Pos_Quat\0");
        b.extend([0; 6]);
        // The report: length 24 + 64, 1 s 500 000 µs, sender 0, type 2.
        b.extend([0, 0, 0, 88, 0, 0, 0, 1, 0, 0x07, 0xa1, 0x20, 0, 0, 0, 0]);
        b.extend([0, 0, 0, 2, 0, 0, 0, 0]);
        b.extend([0, 0, 0, 3, 0, 0, 0, 3]); // sensor, then padding
        for v in [1.0f64, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0] {
            b.extend(v.to_be_bytes());
        }
        assert_eq!(parse_header(&b[..24]).map(|h| h.time), Ok((0, 0)));
        let mut s = Stream::default();
        s.push(&b);
        let Some(Event::Pose { sender, pose }) = s.next_event().unwrap() else {
            panic!("no report");
        };
        assert_eq!(sender, "VRPN Control");
        assert_eq!(pose.sensor, 3);
        assert_eq!(pose.position, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(pose.orientation, DQuat::IDENTITY);
        assert_eq!(s.next_event().unwrap(), None);
        // The same report as `encode` writes it.
        let ours = encode(
            0,
            2,
            (1, 500_000),
            &encode_pos_quat(3, DVec3::new(1.0, 2.0, 3.0), DQuat::IDENTITY),
        );
        assert_eq!(ours[..20], b[b.len() - 88..b.len() - 68]);
        assert_eq!(ours[24..32], [0, 0, 0, 3, 0, 0, 0, 0]);
        assert_eq!(ours[32..], b[b.len() - 56..]);
    }

    #[test]
    fn bad_reports_are_refused_alone_and_bad_frames_end_the_stream() {
        let mut s = Stream::default();
        s.push(&encode_description(TYPE_DESCRIPTION, 1, POS_QUAT));
        let nan = encode_pos_quat(0, DVec3::new(f64::NAN, 0.0, 0.0), DQuat::IDENTITY);
        s.push(&encode(0, 1, (0, 0), &nan));
        let zero = encode_pos_quat(0, DVec3::ZERO, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0));
        s.push(&encode(0, 1, (0, 0), &zero));
        s.push(&encode(0, 1, (0, 0), &[1, 2, 3]));
        s.push(&encode(
            0,
            1,
            (0, 0),
            &encode_pos_quat(0, DVec3::X, DQuat::IDENTITY),
        ));
        let mut fields = Vec::new();
        while let Some(e) = s.next_event().unwrap() {
            match e {
                Event::Refused(e) => fields.push(e.field),
                Event::Pose { pose, .. } => assert_eq!(pose.position, DVec3::X),
                Event::Disconnect => panic!(),
            }
        }
        assert_eq!(
            fields,
            ["Pos_Quat.position", "Pos_Quat.quaternion", "Pos_Quat"]
        );
        // A length no header can have: the framing is lost.
        let mut bad = encode(0, 1, (0, 0), &[]);
        bad[..4].copy_from_slice(&(-3i32).to_be_bytes());
        s.push(&bad);
        let e = s.next_event().unwrap_err();
        assert_eq!(e.field, "header.length");
        assert!(e.to_string().contains("-3 is not 24"), "{e}");
        let mut s = Stream::default();
        s.push(&encode(0, DISCONNECT, (0, 0), &[]));
        assert_eq!(s.next_event().unwrap(), Some(Event::Disconnect));
    }

    /// A server describing 10 000 senders with 32 kB names, then 10 000
    /// with short ones: no long name is kept, at most [`MAX_NAMES`] short
    /// ones are (the newest), and the stream goes on.
    #[test]
    fn a_flood_of_descriptions_keeps_the_names_bounded() {
        let mut s = Stream::default();
        s.push(&encode_description(TYPE_DESCRIPTION, 1, POS_QUAT));
        let long = "x".repeat(32 * 1024);
        let mut refused = 0;
        for id in 0..10_000 {
            s.push(&encode_description(SENDER_DESCRIPTION, id, &long));
            while let Some(e) = s.next_event().unwrap() {
                match e {
                    Event::Refused(e) => {
                        assert_eq!(e.field, "description.name");
                        assert!(e.message.contains("32768 bytes, longer than 255"), "{e}");
                        refused += 1;
                    }
                    e => panic!("{e:?}"),
                }
            }
        }
        assert_eq!(refused, 10_000);
        assert_eq!(s.names_kept(), (0, 1));
        for id in 0..10_000 {
            s.push(&encode_description(
                SENDER_DESCRIPTION,
                id,
                &format!("Body{id}"),
            ));
            assert_eq!(s.next_event().unwrap(), None);
            assert!(s.names_kept().0 <= MAX_NAMES);
        }
        assert_eq!(s.names_kept(), (MAX_NAMES, 1));
        // The newest are kept, the oldest forgotten; the report type stays.
        s.push(&encode(
            9_999,
            1,
            (0, 0),
            &encode_pos_quat(0, DVec3::X, DQuat::IDENTITY),
        ));
        assert!(
            matches!(s.next_event().unwrap(), Some(Event::Pose { sender, .. }) if sender == "Body9999")
        );
        s.push(&encode(
            0,
            1,
            (0, 0),
            &encode_pos_quat(0, DVec3::X, DQuat::IDENTITY),
        ));
        assert!(
            matches!(s.next_event().unwrap(), Some(Event::Pose { sender, .. }) if sender == "?0")
        );
        // The buffer holds no more than the unread part of one message.
        assert!(s.buffer.len() - s.start < HEADER_LEN + MAX_PAYLOAD);
        // The device followed is never forgotten.
        let mut s = Stream::following("Head");
        s.push(&encode_description(SENDER_DESCRIPTION, 0, "Head"));
        s.push(&encode_description(TYPE_DESCRIPTION, 1, POS_QUAT));
        for id in 1..10_000 {
            s.push(&encode_description(
                SENDER_DESCRIPTION,
                id,
                &format!("Body{id}"),
            ));
            s.push(&encode_description(
                TYPE_DESCRIPTION,
                id + 1,
                &format!("Type{id}"),
            ));
            assert_eq!(s.next_event().unwrap(), None);
        }
        assert_eq!(s.names_kept(), (MAX_NAMES, MAX_NAMES));
        s.push(&encode(
            0,
            1,
            (0, 0),
            &encode_pos_quat(0, DVec3::X, DQuat::IDENTITY),
        ));
        assert!(
            matches!(s.next_event().unwrap(), Some(Event::Pose { sender, .. }) if sender == "Head")
        );
    }

    /// Every report the guide (docs/guide/src/tracker.md) says is dropped is refused, with the field
    /// and what was there; a rotation of any finite length is normalised.
    #[test]
    fn reports_beyond_the_room_or_without_a_rotation_are_refused() {
        let q = DQuat::IDENTITY;
        for (p, q, field, says) in [
            (
                DVec3::new(1e300, 0.0, 0.0),
                q,
                "Pos_Quat.position",
                "beyond ±1 km",
            ),
            (
                DVec3::new(0.0, 1e6, 0.0),
                q,
                "Pos_Quat.position",
                "beyond ±1 km",
            ),
            (
                DVec3::new(0.0, 0.0, f64::INFINITY),
                q,
                "Pos_Quat.position",
                "not finite",
            ),
            (
                DVec3::ZERO,
                DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0),
                "Pos_Quat.quaternion",
                "(0.0, 0.0, 0.0, 0.0) is not a rotation",
            ),
            (
                DVec3::ZERO,
                DQuat::from_xyzw(0.0, f64::NAN, 0.0, 1.0),
                "Pos_Quat.quaternion",
                "not a rotation",
            ),
        ] {
            let e = parse_pos_quat(&encode_pos_quat(0, p, q)).unwrap_err();
            assert_eq!(e.field, field);
            assert!(e.message.contains(says), "{e}");
        }
        let big = DQuat::from_xyzw(0.0, 1e300, 0.0, 1e300);
        let pose = parse_pos_quat(&encode_pos_quat(0, DVec3::splat(999.0), big)).unwrap();
        let half = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (pose.orientation.y - half).abs() < 1e-15 && (pose.orientation.w - half).abs() < 1e-15
        );
    }
}
