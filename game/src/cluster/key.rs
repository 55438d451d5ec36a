//! The CAVE's cluster key: the shared secret a render cluster's master and
//! nodes prove they hold before Zenoh lets them talk.
//!
//! A key file (`lightcone cluster-key CAVE.toml` writes `CAVE.key` beside
//! the CAVE file, readable by its owner only) holds one line,
//! `lightcone:<64 hex digits>`: 256 random bits. The master reads the key
//! beside its `--cave` file, a node the file `--key FILE` names (a copy).
//!
//! It is used as Zenoh's user/password authentication (`auth_usrpwd`,
//! `zenoh-transport`'s `establishment/ext/auth/usrpwd.rs`): the master
//! (the only process that listens) accepts a transport only from a peer
//! that answers its random 64-bit challenge with HMAC(challenge, key), so a
//! process without the key is refused before it can declare a publisher,
//! a subscriber, a queryable or a liveliness token under the cluster's
//! keys. What it does not do: the master does not prove the key to the
//! node (a node that is pointed at a stranger's endpoint is not refused by
//! Zenoh), and the traffic is not encrypted (a process that can read the
//! network sees the frames). Each message (frame, swap, ready answer,
//! snapshot) is therefore also signed with the key ([`ClusterKey::seal`]:
//! HMAC-SHA3-256 over its kind and its bytes), and a node or master drops
//! what is not signed with it ([`ClusterKey::open`]); the liveliness tokens
//! carry no payload and rest on the transport's authentication alone.

use std::path::{Path, PathBuf};

/// The Zenoh user name of every cluster process.
pub const USER: &str = "lightcone";
/// Random bytes in a key.
pub const KEY_BYTES: usize = 32;

/// A cluster key read from its file.
#[derive(Clone)]
pub struct ClusterKey {
    /// The key file (the master's Zenoh reads it as its user/password
    /// dictionary).
    pub path: PathBuf,
    /// The secret, as the 64 hex digits of the file.
    secret: String,
}

impl std::fmt::Debug for ClusterKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ClusterKey({})", self.path.display())
    }
}

/// The key file of a CAVE file: beside it, `.key` for `.toml`.
pub fn beside(cave: &Path) -> PathBuf {
    cave.with_extension("key")
}

/// Writes a new random key to `path` (readable by its owner only). An
/// existing file is kept unless `replace`: the nodes hold copies of it.
///
/// # Errors
/// The file exists (and not `replace`), or cannot be written, or the
/// system has no random source; the message names the file.
pub fn generate(path: &Path, replace: bool) -> Result<(), String> {
    use std::io::{Read, Write};
    let mut random = [0u8; KEY_BYTES];
    std::fs::File::open("/dev/urandom")
        .and_then(|mut f| f.read_exact(&mut random))
        .map_err(|e| format!("cannot draw a random key from /dev/urandom: {e}"))?;
    let hex: String = random.iter().map(|b| format!("{b:02x}")).collect();
    let mut options = std::fs::OpenOptions::new();
    options.write(true);
    if replace {
        options.create(true).truncate(true);
    } else {
        options.create_new(true);
    }
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o600);
    let mut file = options.open(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::AlreadyExists {
            format!(
                "{}: a cluster key is already there (the render nodes hold copies of it); \
                 give --replace to make a new one",
                path.display()
            )
        } else {
            format!("{}: {e}", path.display())
        }
    })?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o600))
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    writeln!(file, "{USER}:{hex}").map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads and checks a key file.
///
/// # Errors
/// The file cannot be read, or is not one line `lightcone:<64 hex
/// digits>`; the message names the file and says how to make one.
pub fn load(path: &Path) -> Result<ClusterKey, String> {
    let how = "make one with `lightcone cluster-key CAVE.toml` on the master and copy it \
               to every render node";
    let text = std::fs::read_to_string(path).map_err(|e| {
        format!(
            "{}: cannot read the cluster key ({e}): {how}",
            path.display()
        )
    })?;
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let secret = match (lines.next(), lines.next()) {
        (Some(line), None) => line
            .strip_prefix(USER)
            .and_then(|r| r.strip_prefix(':'))
            .filter(|h| h.len() == 2 * KEY_BYTES && h.bytes().all(|b| b.is_ascii_hexdigit())),
        _ => None,
    };
    let Some(secret) = secret else {
        return Err(format!(
            "{}: not a cluster key (one line, `{USER}:` and {} hex digits): {how}",
            path.display(),
            2 * KEY_BYTES
        ));
    };
    Ok(ClusterKey {
        path: path.to_owned(),
        secret: secret.to_ascii_lowercase(),
    })
}

impl ClusterKey {
    /// The secret's bytes, for signing messages.
    pub fn secret(&self) -> &[u8] {
        self.secret.as_bytes()
    }

    /// Sets Zenoh's user/password authentication in `config`: the
    /// credentials this process answers a challenge with and, for the one
    /// that listens, the dictionary it checks the others' against (the
    /// key file itself, `user:password` per line as Zenoh reads it).
    pub fn configure(&self, config: &mut zenoh::Config, listen: bool) -> Result<(), String> {
        let json = |v: &str| serde_json::to_string(v).unwrap_or_default();
        let mut set = |key: &str, value: String| {
            config
                .insert_json5(key, &value)
                .map_err(|e| format!("Zenoh configuration {key}: {e}"))
        };
        set("transport/auth/usrpwd/user", json(USER))?;
        set("transport/auth/usrpwd/password", json(&self.secret))?;
        if listen {
            set(
                "transport/auth/usrpwd/dictionary_file",
                json(&self.path.to_string_lossy()),
            )?;
        }
        Ok(())
    }
}

/// Bytes of a message's signature (HMAC-SHA3-256).
pub const TAG_BYTES: usize = 32;

type Mac = hmac::Hmac<sha3::Sha3_256>;

impl ClusterKey {
    fn mac(&self, kind: &str, bytes: &[u8]) -> Mac {
        use hmac::Mac as _;
        // A key of any length is accepted by HMAC.
        let mut mac = Mac::new_from_slice(self.secret()).expect("HMAC takes any key length");
        mac.update(kind.as_bytes());
        mac.update(&[0]);
        mac.update(bytes);
        mac
    }

    /// `bytes` (a message of kind `kind`: `frame`, `swap`, `ready`,
    /// `snapshot`) followed by its signature.
    pub fn seal(&self, kind: &str, mut bytes: Vec<u8>) -> Vec<u8> {
        use hmac::Mac as _;
        let tag = self.mac(kind, &bytes).finalize().into_bytes();
        bytes.extend_from_slice(&tag);
        bytes
    }

    /// The message of a sealed `kind` message, if it was signed with this
    /// key (compared in constant time).
    ///
    /// # Errors
    /// Too short to hold a signature, or signed with another key or as
    /// another kind: the message says which kind and its length.
    pub fn open<'a>(&self, kind: &str, sealed: &'a [u8]) -> Result<&'a [u8], String> {
        use hmac::Mac as _;
        let refused = || {
            format!(
                "a {kind} ({} bytes) not signed with this cluster's key",
                sealed.len()
            )
        };
        let split = sealed.len().checked_sub(TAG_BYTES).ok_or_else(refused)?;
        let (bytes, tag) = sealed.split_at(split);
        self.mac(kind, bytes)
            .verify_slice(tag)
            .map_err(|_| refused())?;
        Ok(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_generated_key_loads_is_private_and_is_not_overwritten() {
        let dir = std::env::temp_dir().join(format!("lightcone-key-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = beside(&dir.join("cave.toml"));
        assert_eq!(path, dir.join("cave.key"));
        let _ = std::fs::remove_file(&path);
        generate(&path, false).unwrap();
        let key = load(&path).unwrap();
        assert_eq!(key.secret().len(), 64);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o600);
        }
        let e = generate(&path, false).unwrap_err();
        assert!(e.contains("already there"), "{e}");
        assert_eq!(load(&path).unwrap().secret(), key.secret());
        generate(&path, true).unwrap();
        assert_ne!(load(&path).unwrap().secret(), key.secret(), "a new key");
        for bad in ["", "lightcone:abc\n", "other:00\n", "lightcone:zz\nx\n"] {
            std::fs::write(&path, bad).unwrap();
            let e = load(&path).unwrap_err();
            assert!(e.contains("not a cluster key"), "{bad:?}: {e}");
        }
        // A message signed with one key opens with it only, as its kind only.
        let other = ClusterKey {
            path: path.clone(),
            secret: "0".repeat(64),
        };
        let sealed = key.seal("frame", vec![1, 2, 3]);
        assert_eq!(sealed.len(), 3 + TAG_BYTES);
        assert_eq!(key.open("frame", &sealed), Ok(&[1u8, 2, 3][..]));
        let e = other.open("frame", &sealed).unwrap_err();
        assert_eq!(e, "a frame (35 bytes) not signed with this cluster's key");
        assert!(key.open("ready", &sealed).is_err(), "another kind");
        let mut forged = sealed.clone();
        forged[1] ^= 1;
        assert!(key.open("frame", &forged).is_err(), "a changed byte");
        assert!(key.open("frame", &sealed[..10]).is_err(), "too short");
        assert!(key.open("frame", &[1, 2, 3]).is_err(), "unsigned");
        let e = load(&dir.join("none.key")).unwrap_err();
        assert!(e.contains("cannot read the cluster key"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
