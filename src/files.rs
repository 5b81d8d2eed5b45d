//! Where the bytes a lesson reads come from: the file system, or, in the WebAssembly build
//! (the live lab in a browser, which has no file system), the files the page hands over with
//! [`provide`]. Every read of a lesson's assets goes through here, so the same validation and
//! the same error messages hold in both builds.

use std::io;
use std::path::{Path, PathBuf};

/// What a lesson needs to know of a file before reading it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Meta {
    /// Its length in bytes.
    pub len: u64,
    /// When it was last written (`None` where unknown, as for files in memory).
    pub modified: Option<std::time::SystemTime>,
    /// What it is.
    pub kind: Kind,
}

/// What kind of file a path names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A regular file.
    File,
    /// A folder.
    Folder,
    /// A FIFO.
    Fifo,
    /// A socket.
    Socket,
    /// A device.
    Device,
    /// Anything else.
    Other,
}

impl Kind {
    /// What the kind is called in a message, with its article.
    pub fn described(self) -> &'static str {
        match self {
            Kind::File => "regular file",
            Kind::Folder => "a folder",
            Kind::Fifo => "a FIFO (named pipe)",
            Kind::Socket => "a socket",
            Kind::Device => "a device",
            Kind::Other => "a special file",
        }
    }
}

/// The whole file.
///
/// # Errors
/// The operating system's (or, in memory, `NotFound`).
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    read_limited(path, u64::MAX - 1)
}

/// At most `limit + 1` bytes of the file, so that a caller sees a file that grew past its
/// limit after it was measured.
///
/// # Errors
/// As [`read`].
pub fn read_limited(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let file = std::fs::File::open(path)?;
        let mut raw = Vec::new();
        io::Read::read_to_end(&mut io::Read::take(file, limit.saturating_add(1)), &mut raw)?;
        Ok(raw)
    }
    #[cfg(target_arch = "wasm32")]
    {
        let f = memory::get(path)?;
        Ok(f[..f.len().min(usize::try_from(limit.saturating_add(1)).unwrap_or(usize::MAX))].to_vec())
    }
}

/// An image reader over the file's bytes, its format guessed from them.
///
/// # Errors
/// As [`read`].
pub fn image_reader(path: &Path) -> io::Result<image::ImageReader<io::Cursor<Vec<u8>>>> {
    image::ImageReader::new(io::Cursor::new(read(path)?)).with_guessed_format()
}

/// The file's length, time and kind (symlinks followed).
///
/// # Errors
/// As [`read`].
pub fn metadata(path: &Path) -> io::Result<Meta> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        let m = std::fs::metadata(path)?;
        let t = m.file_type();
        let mut kind = if t.is_file() {
            Kind::File
        } else if t.is_dir() {
            Kind::Folder
        } else {
            Kind::Other
        };
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if t.is_fifo() {
                kind = Kind::Fifo;
            } else if t.is_socket() {
                kind = Kind::Socket;
            } else if t.is_block_device() || t.is_char_device() {
                kind = Kind::Device;
            }
        }
        Ok(Meta { len: m.len(), modified: m.modified().ok(), kind })
    }
    #[cfg(target_arch = "wasm32")]
    {
        memory::metadata(path)
    }
}

/// The absolute path with `.`, `..` and (on a file system) symlinks resolved.
///
/// # Errors
/// `NotFound` when nothing is there.
pub fn canonicalize(path: &Path) -> io::Result<PathBuf> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        path.canonicalize()
    }
    #[cfg(target_arch = "wasm32")]
    {
        let p = memory::normal(path);
        memory::metadata(&p).map(|_| p)
    }
}

/// `path` made absolute (against the current folder; in memory, against `/`).
///
/// # Errors
/// When the current folder is unknown.
pub fn absolute(path: &Path) -> io::Result<PathBuf> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        std::path::absolute(path)
    }
    #[cfg(target_arch = "wasm32")]
    {
        Ok(memory::normal(path))
    }
}

/// Hands a file to the WebAssembly build, at `path` (relative paths are under `/`). On a
/// file system this does nothing: the files are read where they are.
pub fn provide(path: &Path, bytes: Vec<u8>) {
    #[cfg(target_arch = "wasm32")]
    memory::put(path, bytes);
    #[cfg(not(target_arch = "wasm32"))]
    let _ = (path, bytes);
}

/// The files the WebAssembly build was given: a map from normalized absolute paths.
#[cfg(target_arch = "wasm32")]
mod memory {
    use super::{Kind, Meta};
    use std::collections::BTreeMap;
    use std::io;
    use std::path::{Component, Path, PathBuf};
    use std::sync::{Arc, RwLock};

    static FILES: RwLock<BTreeMap<PathBuf, Arc<[u8]>>> = RwLock::new(BTreeMap::new());

    /// `path` under `/`, with `.` and `..` resolved by name.
    pub(super) fn normal(path: &Path) -> PathBuf {
        let mut out = PathBuf::from("/");
        for c in path.components() {
            match c {
                Component::ParentDir => {
                    out.pop();
                }
                Component::Normal(n) => out.push(n),
                _ => {}
            }
        }
        out
    }

    pub(super) fn put(path: &Path, bytes: Vec<u8>) {
        FILES.write().unwrap_or_else(|e| e.into_inner()).insert(normal(path), bytes.into());
    }

    pub(super) fn get(path: &Path) -> io::Result<Arc<[u8]>> {
        let files = FILES.read().unwrap_or_else(|e| e.into_inner());
        files.get(&normal(path)).cloned().ok_or_else(|| io::Error::from(io::ErrorKind::NotFound))
    }

    pub(super) fn metadata(path: &Path) -> io::Result<Meta> {
        let p = normal(path);
        let files = FILES.read().unwrap_or_else(|e| e.into_inner());
        if let Some(f) = files.get(&p) {
            return Ok(Meta { len: f.len() as u64, modified: None, kind: Kind::File });
        }
        // A folder is any prefix of a file's path (the root always is).
        if p == Path::new("/") || files.keys().any(|k| k.starts_with(&p)) {
            return Ok(Meta { len: 0, modified: None, kind: Kind::Folder });
        }
        Err(io::Error::from(io::ErrorKind::NotFound))
    }
}
