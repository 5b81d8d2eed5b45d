//! The one cache of deterministic, expensive results (references, rendered figure cells),
//! kept on disk across runs and keyed by everything they depend on.
//!
//! A [`Key`] hashes (BLAKE3) the program itself (the running executable's bytes, so a
//! rebuilt program never reads an older one's results), the kind of result and the
//! caller's inputs (the lesson's validated content, the settings, the contents of every
//! file it reads). An entry is one file, `<dir>/<kind>/<key>.bin`: a header, the key, the
//! payload and the payload's hash. A read checks all four; a stale, truncated or corrupt
//! entry is removed and reported as a miss, so it is recomputed, never used. A write goes
//! to a uniquely named temporary file in the same folder and is renamed into place, so a
//! reader never sees half an entry and two processes writing the same key both leave a
//! whole one (the same bytes: the result is deterministic).
//!
//! The cache is off until [`configure`] turns it on (the command line does, see
//! docs/cli.md), so the library and its tests never write outside their own folders.
//! Errors writing it are never fatal: the result is simply not kept.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::RwLock;
use std::sync::atomic::{AtomicU64, Ordering};

/// Results faster to compute than this (milliseconds) are not kept: reading them back would
/// cost about as much.
pub const MIN_KEPT_MS: f64 = 20.0;

/// The first bytes of every entry (with the format's version).
const MAGIC: &[u8; 16] = b"shadelab-cache1\n";

/// The folder results are kept in, or `None` when the cache is off.
static DIR: RwLock<Option<PathBuf>> = RwLock::new(None);

/// Entries read, missed (absent) and dropped (corrupt or stale) in this process.
static HITS: AtomicU64 = AtomicU64::new(0);
static MISSES: AtomicU64 = AtomicU64::new(0);
static DROPPED: AtomicU64 = AtomicU64::new(0);
/// Temporary files written by this process (their names must not collide).
static TEMPS: AtomicU64 = AtomicU64::new(0);

/// Turns the cache on in `dir` (created on the first write), or off with `None`.
pub fn configure(dir: Option<PathBuf>) {
    *DIR.write().unwrap_or_else(|e| e.into_inner()) = dir;
}

/// The folder in use, or `None` when the cache is off.
pub fn dir() -> Option<PathBuf> {
    DIR.read().unwrap_or_else(|e| e.into_inner()).clone()
}

/// The default folder: `$SHADELAB_CACHE_DIR`, else the platform's cache folder
/// (`$XDG_CACHE_HOME` or `~/.cache` on Linux, `~/Library/Caches` on macOS, `%LOCALAPPDATA%`
/// on Windows) with `shadelab` under it; `None` when `$SHADELAB_NO_CACHE` is set (to any
/// value but the empty one) or no such folder is known.
pub fn default_dir() -> Option<PathBuf> {
    if std::env::var_os("SHADELAB_NO_CACHE").is_some_and(|v| !v.is_empty()) {
        return None;
    }
    match std::env::var_os("SHADELAB_CACHE_DIR").filter(|v| !v.is_empty()) {
        Some(d) => Some(PathBuf::from(d)),
        None => dirs::cache_dir().map(|d| d.join("shadelab")),
    }
}

/// How the cache served this process: entries read, absent, and found corrupt or stale.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// Entries read and used.
    pub hits: u64,
    /// Entries looked for and absent.
    pub misses: u64,
    /// Entries found unusable (truncated, corrupt, another key's), removed and recomputed.
    pub dropped: u64,
}

/// The counts so far in this process.
pub fn counts() -> Counts {
    Counts { hits: HITS.load(Ordering::Relaxed), misses: MISSES.load(Ordering::Relaxed), dropped: DROPPED.load(Ordering::Relaxed) }
}

/// A hash of the running program, computed once: the executable's bytes (a rebuild with
/// any change gives another), or the version when the executable cannot be read.
fn program() -> &'static [u8; 32] {
    static ID: std::sync::OnceLock<[u8; 32]> = std::sync::OnceLock::new();
    ID.get_or_init(|| {
        let mut h = blake3::Hasher::new();
        h.update(env!("CARGO_PKG_VERSION").as_bytes());
        if let Some(exe) = std::env::current_exe().ok().and_then(|p| std::fs::read(p).ok()) {
            h.update(&exe);
        }
        *h.finalize().as_bytes()
    })
}

/// What a cached result depends on, hashed part by part (each part length-prefixed, so
/// `("ab", "c")` and `("a", "bc")` differ).
#[derive(Debug, Clone)]
pub struct KeyBuilder {
    hasher: blake3::Hasher,
    kind: &'static str,
}

impl KeyBuilder {
    /// A key for results of `kind` (a folder name: letters, digits, `-`), for this program.
    pub fn new(kind: &'static str) -> KeyBuilder {
        let mut hasher = blake3::Hasher::new();
        hasher.update(program());
        let mut k = KeyBuilder { hasher, kind };
        k.part(kind.as_bytes());
        k
    }

    /// Adds one input.
    pub fn part(&mut self, bytes: &[u8]) -> &mut KeyBuilder {
        self.hasher.update(&(bytes.len() as u64).to_le_bytes());
        self.hasher.update(bytes);
        self
    }

    /// Adds a file's path and contents; `None` when it cannot be read (then nothing that
    /// depends on it should be cached).
    pub fn file(&mut self, path: &Path) -> Option<&mut KeyBuilder> {
        let bytes = crate::files::read(path).ok()?;
        self.part(path.as_os_str().as_encoded_bytes());
        Some(self.part(&bytes))
    }

    /// The key.
    pub fn finish(&self) -> Key {
        Key { hash: *self.hasher.finalize().as_bytes(), kind: self.kind }
    }
}

/// The identity of one cached result.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    hash: [u8; 32],
    kind: &'static str,
}

impl Key {
    /// The entry's file under `dir`.
    fn path(&self, dir: &Path) -> PathBuf {
        let hex: String = self.hash.iter().map(|b| format!("{b:02x}")).collect();
        dir.join(self.kind).join(format!("{hex}.bin"))
    }
}

/// The payload stored under `key`, or `None` (cache off, absent, or unusable: then the
/// entry is removed).
pub fn get(key: &Key) -> Option<Vec<u8>> {
    let path = key.path(&dir()?);
    let Ok(bytes) = std::fs::read(&path) else {
        MISSES.fetch_add(1, Ordering::Relaxed);
        return None;
    };
    match unpack(&bytes, key) {
        Some(payload) => {
            HITS.fetch_add(1, Ordering::Relaxed);
            Some(payload.to_vec())
        }
        None => {
            DROPPED.fetch_add(1, Ordering::Relaxed);
            let _ = std::fs::remove_file(&path);
            None
        }
    }
}

/// The payload of an entry's bytes when they are whole and for `key`.
fn unpack<'a>(bytes: &'a [u8], key: &Key) -> Option<&'a [u8]> {
    let rest = bytes.strip_prefix(MAGIC)?;
    let (stored_key, rest) = rest.split_at_checked(32)?;
    let (len, rest) = rest.split_at_checked(8)?;
    let len = usize::try_from(u64::from_le_bytes(len.try_into().ok()?)).ok()?;
    let (payload, sum) = rest.split_at_checked(len)?;
    (stored_key == key.hash && sum == blake3::hash(payload).as_bytes()).then_some(payload)
}

/// Keeps `payload` under `key` when the cache is on; never fails (a result that cannot be
/// kept is recomputed next time).
pub fn put(key: &Key, payload: &[u8]) {
    if let Some(dir) = dir() {
        let _ = write(&key.path(&dir), key, payload);
    }
}

/// Writes one entry atomically: a temporary file beside it, then a rename.
fn write(path: &Path, key: &Key, payload: &[u8]) -> std::io::Result<()> {
    let folder = path.parent().expect("an entry is inside its kind's folder");
    std::fs::create_dir_all(folder)?;
    let n = TEMPS.fetch_add(1, Ordering::Relaxed);
    let tmp = folder.join(format!(".tmp-{}-{n}", std::process::id()));
    let result = (|| {
        let mut f = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        f.write_all(MAGIC)?;
        f.write_all(&key.hash)?;
        f.write_all(&(payload.len() as u64).to_le_bytes())?;
        f.write_all(payload)?;
        f.write_all(blake3::hash(payload).as_bytes())?;
        f.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Reads a payload back, little-endian, in the order it was written: each read is `None`
/// past the end, so a short payload is refused, never a panic.
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    rest: &'a [u8],
}

impl<'a> Reader<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Reader<'a> {
        Reader { rest: bytes }
    }

    /// The next `n` bytes.
    pub fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let (head, rest) = self.rest.split_at_checked(n)?;
        self.rest = rest;
        Some(head)
    }

    /// The next byte.
    pub fn u8(&mut self) -> Option<u8> {
        Some(self.take(1)?[0])
    }

    /// The next `u32`.
    pub fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }

    /// The next `f64`.
    pub fn f64(&mut self) -> Option<f64> {
        Some(f64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }

    /// The next `n` `f32`s.
    pub fn f32s(&mut self, n: usize) -> Option<Vec<f32>> {
        let bytes = self.take(n.checked_mul(4)?)?;
        Some(bytes.chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().expect("four bytes"))).collect())
    }

    /// The next `n` RGB triples of `f32`.
    pub fn vec3s(&mut self, n: usize) -> Option<Vec<glam::Vec3>> {
        Some(self.f32s(n.checked_mul(3)?)?.chunks_exact(3).map(glam::Vec3::from_slice).collect())
    }

    /// True when every byte was read.
    pub fn is_done(&self) -> bool {
        self.rest.is_empty()
    }
}

/// `f32`s as little-endian bytes appended to `out`, every bit kept.
pub fn put_f32s(out: &mut Vec<u8>, values: impl IntoIterator<Item = f32>) {
    out.extend(values.into_iter().flat_map(f32::to_le_bytes));
}

/// The entries under `dir` and their total size in bytes.
pub fn usage(dir: &Path) -> (u64, u64) {
    let mut entries = 0;
    let mut bytes = 0;
    for kind in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        for e in std::fs::read_dir(kind.path()).into_iter().flatten().flatten() {
            if e.path().extension().is_some_and(|x| x == "bin") {
                entries += 1;
                bytes += e.metadata().map_or(0, |m| m.len());
            }
        }
    }
    (entries, bytes)
}

/// Removes every entry under `dir` (and temporary files left by a killed process); the
/// number of files removed.
///
/// # Errors
/// The first entry that could not be removed.
pub fn clear(dir: &Path) -> std::io::Result<u64> {
    let mut removed = 0;
    for kind in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if !kind.path().is_dir() {
            continue;
        }
        for e in std::fs::read_dir(kind.path())?.flatten() {
            let name = e.file_name();
            let name = name.to_string_lossy();
            if name.ends_with(".bin") || name.starts_with(".tmp-") {
                std::fs::remove_file(e.path())?;
                removed += 1;
            }
        }
        let _ = std::fs::remove_dir(kind.path());
    }
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(s: &str) -> Key {
        KeyBuilder::new("test").part(s.as_bytes()).finish()
    }

    #[test]
    fn parts_are_length_prefixed_and_kinds_differ() {
        let ab_c = KeyBuilder::new("test").part(b"ab").part(b"c").finish();
        let a_bc = KeyBuilder::new("test").part(b"a").part(b"bc").finish();
        assert_ne!(ab_c, a_bc);
        assert_ne!(KeyBuilder::new("a").finish().hash, KeyBuilder::new("b").finish().hash);
        assert_eq!(key("x"), key("x"));
    }

    #[test]
    fn an_entry_round_trips_and_any_damage_is_a_miss() {
        let dir = tempfile::tempdir().unwrap();
        let k = key("round trip");
        let path = k.path(dir.path());
        write(&path, &k, b"payload bytes").unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(unpack(&bytes, &k), Some(&b"payload bytes"[..]));
        // Another key's entry, a flipped payload byte, a truncation, a wrong header.
        assert_eq!(unpack(&bytes, &key("other")), None);
        let mut flipped = bytes.clone();
        flipped[MAGIC.len() + 32 + 8 + 3] ^= 1;
        assert_eq!(unpack(&flipped, &k), None);
        for cut in [0, 10, MAGIC.len() + 20, bytes.len() - 1] {
            assert_eq!(unpack(&bytes[..cut], &k), None, "cut at {cut}");
        }
        let mut header = bytes.clone();
        header[0] = b'S';
        assert_eq!(unpack(&header, &k), None);
        // A length field beyond the file is a miss, not a panic.
        let mut long = bytes;
        long[MAGIC.len() + 32..MAGIC.len() + 40].copy_from_slice(&u64::MAX.to_le_bytes());
        assert_eq!(unpack(&long, &k), None);
    }

    #[test]
    fn writers_racing_on_one_key_leave_a_whole_entry_and_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let k = key("race");
        let path = k.path(dir.path());
        let payload: Vec<u8> = (0..200_000u32).map(|i| (i % 251) as u8).collect();
        std::thread::scope(|s| {
            for _ in 0..8 {
                s.spawn(|| write(&path, &k, &payload).unwrap());
            }
        });
        assert_eq!(unpack(&std::fs::read(&path).unwrap(), &k), Some(&payload[..]));
        let files: Vec<_> = std::fs::read_dir(path.parent().unwrap()).unwrap().flatten().map(|e| e.file_name()).collect();
        assert_eq!(files.len(), 1, "{files:?}");
        assert_eq!(usage(dir.path()), (1, std::fs::metadata(&path).unwrap().len()));
        assert_eq!(clear(dir.path()).unwrap(), 1);
        assert_eq!(usage(dir.path()), (0, 0));
    }
}
