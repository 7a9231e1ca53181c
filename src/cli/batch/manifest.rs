//! `DIR/manifest.jsonl`: one JSON line per input of the last run, each
//! written whole and made durable (`fsync`) as its file finishes, so a run
//! killed at any moment leaves whole lines (a torn last one, from a kill
//! inside a write, is ignored when the manifest is read back). What a run
//! finds there decides what it skips: an input whose line says it was
//! done (or skipped) with the same contents hash and options, whose
//! output is there with the size it was written with.

use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The manifest's name in the batch's folder.
pub(super) const NAME: &str = "manifest.jsonl";

/// What became of an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum Status {
    /// Refined and written by this run.
    Done,
    /// Refused or failed: `error` says why.
    Failed,
    /// Done by an earlier run, its output still there: left as it is.
    Skipped,
}

/// One line of the manifest.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(super) struct Record {
    pub(super) input: String,
    pub(super) output: String,
    pub(super) status: Status,
    /// The one-line error of a failure (the library's, naming the file and
    /// the element).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) error: Option<String>,
    pub(super) input_vertices: Option<usize>,
    pub(super) input_faces: Option<usize>,
    pub(super) vertices: Option<usize>,
    pub(super) faces: Option<usize>,
    /// Seconds the file took (reading, waiting for memory, refining,
    /// writing); for a skipped file, the run that did it.
    pub(super) seconds: f64,
    /// Seconds into the run when the file was given its memory and its
    /// refinement began, and when it was done (none for a file refused
    /// before or a skipped one).
    #[serde(default)]
    pub(super) admitted_at: Option<f64>,
    #[serde(default)]
    pub(super) finished_at: Option<f64>,
    /// The input's contents hash ([`content_hash`]); none for what is not
    /// a file to read.
    pub(super) hash: Option<String>,
    /// The output's size as written.
    pub(super) output_bytes: Option<u64>,
    /// The options given (as the batch's `settings`).
    pub(super) options: serde_json::Value,
}

impl Record {
    /// Whether this line says that `output` was made from `input` with
    /// contents `hash` and `options`, and the output is still there as it
    /// was written.
    pub(super) fn still_done(
        &self,
        input: &str,
        output: &Path,
        hash: Option<&str>,
        options: &serde_json::Value,
    ) -> bool {
        let same = self.input == input && self.output == output.display().to_string() && &self.options == options;
        let written =
            self.output_bytes.is_some() && std::fs::metadata(output).ok().map(|m| m.len()) == self.output_bytes;
        matches!(self.status, Status::Done | Status::Skipped)
            && same
            && hash.is_some()
            && self.hash.as_deref() == hash
            && written
    }
}

/// The lines of the manifest in `dir` by input (the last line of an input
/// wins); a line that does not parse (the torn end of a killed run) is left
/// out. None where there is no manifest.
pub(super) fn previous(dir: &Path) -> HashMap<String, Record> {
    let Ok(text) = std::fs::read_to_string(dir.join(NAME)) else { return HashMap::new() };
    text.lines().filter_map(|l| serde_json::from_str::<Record>(l).ok()).map(|r| (r.input.clone(), r)).collect()
}

/// The manifest being written.
pub(super) struct Manifest {
    file: Mutex<File>,
    path: PathBuf,
}

impl Manifest {
    /// A fresh manifest in `dir` holding `first` (the skipped inputs'
    /// lines): written beside it, made durable and renamed over the last
    /// one, so the last run's lines stay until these replace them.
    pub(super) fn start(dir: &Path, first: &[Record]) -> std::io::Result<Manifest> {
        let path = dir.join(NAME);
        // under the batch's lock on `dir`: no other run uses this name
        let fresh = dir.join(format!(".{NAME}.new"));
        let mut text = Vec::new();
        for r in first {
            text.extend(line(r));
        }
        let mut f = File::create(&fresh)?;
        f.write_all(&text)?;
        f.sync_all()?;
        std::fs::rename(&fresh, &path)?;
        File::open(dir)?.sync_all()?;
        let file = std::fs::OpenOptions::new().append(true).open(&path)?;
        Ok(Manifest { file: Mutex::new(file), path })
    }

    /// Appends `r` as one line, durable when this returns.
    pub(super) fn append(&self, r: &Record) -> std::io::Result<()> {
        let mut f = self.file.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        f.write_all(&line(r))?;
        f.sync_data()
    }

    /// Where it is.
    pub(super) fn path(&self) -> &Path {
        &self.path
    }
}

/// `r` as a line of JSON with its newline.
fn line(r: &Record) -> Vec<u8> {
    // a record of strings, numbers and JSON values always serialises
    let mut l = serde_json::to_vec(r).unwrap_or_default();
    l.push(b'\n');
    l
}

/// The contents hash of a model argument: XXH3's 128 bits of the file's
/// bytes (or of a bundled model's), as `xxh3-128:<32 hex digits>`; `None`
/// for what is not a regular file to read (the library then says what it
/// is). The file is opened without blocking, so a pipe named like a model
/// never stalls the batch.
pub(super) fn content_hash(input: &Path) -> Option<String> {
    use std::os::unix::fs::OpenOptionsExt;
    use twox_hash::XxHash3_128;
    let name = input.to_str().unwrap_or_default();
    if let Some(m) = subdiv::bundled::MODELS.iter().find(|m| m.cli_name() == name) {
        return Some(format!("xxh3-128:{:032x}", XxHash3_128::oneshot(m.bytes)));
    }
    let mut file = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(input).ok()?;
    if !file.metadata().ok()?.is_file() {
        return None;
    }
    let mut hasher = XxHash3_128::new();
    let mut buf = vec![0u8; 1 << 20];
    loop {
        match file.read(&mut buf) {
            Ok(0) => break,
            Ok(k) => hasher.write(&buf[..k]),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(_) => return None,
        }
    }
    Some(format!("xxh3-128:{:032x}", hasher.finish_128()))
}

/// An exclusive lock on the batch's folder for the run (`flock`), so two
/// batches never write one manifest.
pub(super) struct Lock {
    _held: File,
}

impl Lock {
    /// Locks `dir`.
    ///
    /// # Errors
    /// Another batch holds it, or `dir` cannot be opened.
    pub(super) fn take(dir: &Path) -> Result<Lock, String> {
        use std::os::fd::AsRawFd;
        let shown = || subdiv::clean_error(&dir.display().to_string(), 80).into_owned();
        let f = File::open(dir).map_err(|e| format!("{}: {e}", shown()))?;
        // SAFETY: the descriptor is `f`'s, open for the call; flock changes
        // no memory of ours.
        let r = unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
        if r != 0 {
            return Err(format!("{}: another subdiv batch is writing there", shown()));
        }
        Ok(Lock { _held: f })
    }
}
