//! `subdiv batch`: every model of folders, files and globs refined as
//! `subdiv subdivide` refines one (the same function,
//! [`mesh_ops::subdivide_file`], over the library's
//! [`subdiv::subdivide_file`]), several at once within the memory budget,
//! each result a line of the manifest ([`manifest`]) that a run started
//! again resumes from.
//!
//! The scheduler: `--threads` workers (default: one per core) take the
//! files in order. Taking a file is a turn, held by one worker at a time:
//! it reserves what reading the file is expected to take
//! ([`LOAD_FACTOR`] times its bytes), reads it, is told by the library what
//! the refinement will need ([`subdiv::Demand`], from
//! `ControlCounts::peak_bytes`: every level kept, plus [`WRITE_BYTES`] for
//! the writer), trades the first reservation for that one, waiting until it
//! fits beside the files in flight, and only then gives the turn up to
//! refine and write. Only the worker holding the turn ever waits, and the
//! files in flight hold all they will take, so every wait ends: at the
//! latest when the files in flight are done (a reservation is at most the
//! whole budget, and a file alone always fits). A file that the library
//! refuses at this budget whatever path it takes (its least peak over the
//! budget) goes on at once without a reservation: the library refuses it,
//! by its `TooLarge` message, before it allocates.

mod inputs;
mod manifest;

use super::mesh_ops::{self, RefineArgs, Summary};
use manifest::{Manifest, Record, Status};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};
use std::time::Instant;
use subdiv::Demand;

/// Bytes reserved for reading a model, per byte of the file (an OBJ's
/// faces take about 5 bytes of tables per byte of text; 8 for headroom).
const LOAD_FACTOR: u64 = 8;

/// Bytes reserved beside a refinement for writing it (the writers keep
/// about 10 MB of formatted text in flight).
const WRITE_BYTES: u64 = 16 << 20;

/// `subdiv batch` arguments.
#[derive(clap::Args)]
pub struct BatchArgs {
    /// Models: files, folders (searched through for every extension a
    /// reader takes, hidden entries and links to folders left out), globs
    /// (quoted, 'scans/*.ply': matched by subdiv) or bundled:NAME.
    #[arg(required = true, value_name = "INPUT")]
    inputs: Vec<PathBuf>,
    /// The folder of the outputs (made if missing) and of manifest.jsonl;
    /// a folder's models keep their paths under it.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    refine: RefineArgs,
    // the help lists io::write_extensions
    #[arg(long, value_name = "EXT", help = format_help())]
    format: Option<String>,
    /// Print the summary as JSON: files, done, failed, skipped, faces, seconds, manifest.
    #[arg(long)]
    json: bool,
}

/// The help of `--format`: every extension that is written.
fn format_help() -> String {
    let exts: Vec<&str> = subdiv::io::write_extensions().collect();
    format!(
        "The outputs' format, by extension: {}. Default: each input's own where it is written, else obj",
        exts.join(", ")
    )
}

/// What a run did, for its last line or `--json`.
#[derive(Default, Serialize)]
struct Tally {
    files: usize,
    done: usize,
    failed: usize,
    skipped: usize,
    /// Faces written by this run.
    faces: u64,
    seconds: f64,
    manifest: String,
}

/// Why a run stopped before its end.
enum Stop {
    /// Bad arguments: exit code 2.
    Usage(String),
    /// The manifest could not be written: exit code 1.
    Manifest(String),
}

/// `subdiv batch`: its exit code (0 every file done or skipped, 1 some
/// failed, 2 a usage error).
pub(crate) fn batch(a: &BatchArgs) -> ExitCode {
    match run(a) {
        Ok(t) => {
            let shown = match a.json {
                true => super::print_json(&t),
                false => {
                    print_tally(&t);
                    Ok(())
                }
            };
            if let Err(e) = shown {
                eprintln!("subdiv: error: {e}");
                return ExitCode::from(1);
            }
            if t.failed == 0 {
                return ExitCode::SUCCESS;
            }
            eprintln!("subdiv: error: {} of {} files failed (each named in {})", t.failed, t.files, t.manifest);
            ExitCode::from(1)
        }
        Err(Stop::Usage(e)) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::from(2)
        }
        Err(Stop::Manifest(e)) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::from(1)
        }
    }
}

/// The last line of a run.
fn print_tally(t: &Tally) {
    println!(
        "{} files: {} done, {} failed, {} skipped; {} faces in {:.2} s ({}); manifest {}",
        t.files,
        t.done,
        t.failed,
        t.skipped,
        t.faces,
        t.seconds,
        per_second(t.faces, t.seconds),
        t.manifest
    );
}

/// The batch: the inputs gathered, the done ones skipped, the rest refined.
fn run(a: &BatchArgs) -> Result<Tally, Stop> {
    let start = Instant::now();
    let format = output_format(a.format.as_deref())?;
    let shown = |p: &Path| subdiv::clean_error(&p.display().to_string(), 80).into_owned();
    // the arguments checked before anything is made
    let items = inputs::gather(&a.inputs, &a.out, format.as_deref()).map_err(Stop::Usage)?;
    std::fs::create_dir_all(&a.out).map_err(|e| Stop::Usage(format!("--out {}: {e}", shown(&a.out))))?;
    let _lock = manifest::Lock::take(&a.out).map_err(Stop::Usage)?;
    let options = settings();
    let before = manifest::previous(&a.out);
    let hashes: Vec<Option<String>> = {
        use rayon::prelude::*;
        items.par_iter().map(|it| manifest::content_hash(&it.input)).collect()
    };
    let (mut skipped, mut todo) = (Vec::new(), Vec::new());
    for (item, hash) in items.into_iter().zip(hashes) {
        let input = item.input.display().to_string();
        match before.get(&input) {
            Some(r) if r.still_done(&input, &item.output, hash.as_deref(), &options) => {
                skipped.push(Record { status: Status::Skipped, admitted_at: None, finished_at: None, ..r.clone() });
            }
            _ => todo.push((item, hash)),
        }
    }
    let manifest = Manifest::start(&a.out, &skipped)
        .map_err(|e| Stop::Usage(format!("{}: {e}", shown(&a.out.join(manifest::NAME)))))?;
    let limit = a.refine.sub.scheme.max_memory.or_else(subdiv::mem::default_memory_limit).unwrap_or(u64::MAX);
    let mut refine = a.refine.clone();
    // the library refuses at the budget the batch admits by
    refine.sub.scheme.max_memory = Some(limit).filter(|&l| l < u64::MAX);
    let files = skipped.len() + todo.len();
    let progress = Progress::new(todo.len(), skipped.len(), start);
    let batch = Batch {
        todo,
        refine,
        options,
        manifest: &manifest,
        budget: Budget { limit, used: Mutex::new(0), freed: Condvar::new() },
        turn: Mutex::new(0),
        start,
        progress,
        broken: Mutex::new(None),
    };
    let workers = rayon::current_num_threads().clamp(1, batch.todo.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| batch.worker());
        }
    });
    if let Some(e) = lock(&batch.broken).take() {
        return Err(Stop::Manifest(format!("{}: {e}", shown(manifest.path()))));
    }
    let mut t = batch.progress.finish();
    t.files = files;
    t.seconds = start.elapsed().as_secs_f64();
    t.manifest = manifest.path().display().to_string();
    Ok(t)
}

/// `--format`'s extension (lower case, without a dot), refused unless it
/// is written.
fn output_format(format: Option<&str>) -> Result<Option<String>, Stop> {
    let Some(f) = format else { return Ok(None) };
    let ext = f.trim_start_matches('.').to_lowercase();
    let written: Vec<&str> = subdiv::io::write_extensions().collect();
    if !written.contains(&ext.as_str()) {
        let f = subdiv::clean_error(f, 40);
        return Err(Stop::Usage(format!("--format {f}: the outputs are written as one of {}", written.join(", "))));
    }
    Ok(Some(ext))
}

/// The options of the refinement given on the command line, by their long
/// names, with their values as given: what the manifest records and a
/// later run compares before it skips a file. Every option of `subdivide`
/// counts but `--max-memory` and `--limit`, which decide only whether a
/// file is refused, never what is written.
fn settings() -> serde_json::Value {
    use clap::{Args, CommandFactory, parser::ValueSource};
    let Ok(all) = super::Cli::command().try_get_matches_from(std::env::args_os()) else {
        return serde_json::Value::Null;
    };
    let Some(m) = all.subcommand_matches("batch") else { return serde_json::Value::Null };
    let mut map = serde_json::Map::new();
    for arg in RefineArgs::augment_args(clap::Command::new("batch")).get_arguments() {
        let id = arg.get_id().as_str();
        if matches!(id, "max_memory" | "limit") || m.value_source(id) != Some(ValueSource::CommandLine) {
            continue;
        }
        if let Ok(Some(raw)) = m.try_get_raw(id) {
            let values = raw.map(|v| serde_json::Value::from(v.to_string_lossy().into_owned())).collect();
            map.insert(arg.get_long().unwrap_or(id).to_string(), serde_json::Value::Array(values));
        }
    }
    serde_json::Value::Object(map)
}

/// A run in progress: the files to do and what the workers share.
struct Batch<'a> {
    /// The files to refine, with their contents hashes.
    todo: Vec<(inputs::Item, Option<String>)>,
    refine: RefineArgs,
    options: serde_json::Value,
    manifest: &'a Manifest,
    budget: Budget,
    /// The turn to take the next file: the index of the next one.
    turn: Mutex<usize>,
    start: Instant,
    progress: Progress,
    /// The first error writing the manifest: no file is started after it.
    broken: Mutex<Option<std::io::Error>>,
}

impl Batch<'_> {
    /// One worker: files one after another until none is left.
    fn worker(&self) {
        loop {
            let mut turn = lock(&self.turn);
            let i = *turn;
            if i >= self.todo.len() || lock(&self.broken).is_some() {
                return;
            }
            *turn += 1;
            let record = self.one(i, turn);
            self.progress.finished(&record);
            if let Err(e) = self.manifest.append(&record) {
                lock(&self.broken).get_or_insert(e);
            }
        }
    }

    /// File `i`, its turn held until its memory is given: its line of the
    /// manifest. A panic inside is caught and reported as an internal
    /// error, as a last resort: the other files go on.
    fn one(&self, i: usize, turn: MutexGuard<'_, usize>) -> Record {
        let (item, hash) = &self.todo[i];
        let t0 = Instant::now();
        let mut held = Held::new(&self.budget, LOAD_FACTOR.saturating_mul(input_bytes(&item.input)));
        let (mut turn, mut admitted_at) = (Some(turn), None);
        let limit = self.budget.limit;
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            make_folder(&item.output)?;
            let mut admit = |d: &Demand| {
                held.resize(admitted(d, limit));
                admitted_at = Some(self.start.elapsed().as_secs_f64());
                drop(turn.take());
                Ok(())
            };
            mesh_ops::subdivide_file(&item.input, &item.output, &self.refine, &mut admit).map_err(|e| e.to_string())
        }));
        // the end is told before the memory is given back (the next file is
        // admitted after it)
        let end = self.start.elapsed().as_secs_f64();
        drop(turn);
        drop(held);
        let result = result.unwrap_or_else(|panic| Err(format!("internal error: {}", panic_text(&*panic))));
        let finished_at = Some(end).filter(|_| result.is_ok());
        let mut r = record(item, hash.clone(), result, &self.options);
        (r.seconds, r.admitted_at, r.finished_at) = (t0.elapsed().as_secs_f64(), admitted_at, finished_at);
        r
    }
}

/// The bytes a file's refinement is given: [`Demand::peak`] and the
/// writer's, or nothing for a file the library refuses at the budget
/// `limit` before it allocates.
fn admitted(d: &Demand, limit: u64) -> u64 {
    if d.parts == 1 && d.least > limit {
        return 0;
    }
    d.peak.saturating_add(WRITE_BYTES)
}

/// The manifest's line of a file from its result (times filled in by the caller).
fn record(
    item: &inputs::Item,
    hash: Option<String>,
    result: Result<Summary, String>,
    options: &serde_json::Value,
) -> Record {
    let mut r = Record {
        input: item.input.display().to_string(),
        output: item.output.display().to_string(),
        status: Status::Done,
        error: None,
        input_vertices: None,
        input_faces: None,
        vertices: None,
        faces: None,
        seconds: 0.0,
        admitted_at: None,
        finished_at: None,
        hash,
        output_bytes: None,
        options: options.clone(),
    };
    match result {
        Ok(s) => {
            (r.input_vertices, r.input_faces) = (Some(s.input_vertices), Some(s.input_faces));
            (r.vertices, r.faces) = (Some(s.vertices), Some(s.faces));
            r.output_bytes = std::fs::metadata(&item.output).ok().map(|m| m.len());
        }
        Err(e) => {
            r.status = Status::Failed;
            r.error = Some(subdiv::clean_error(&e, 400).into_owned());
        }
    }
    r
}

/// Makes the folder `output` goes in.
fn make_folder(output: &Path) -> Result<(), String> {
    match output.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: {e}", subdiv::clean_error(&dir.display().to_string(), 80))),
        _ => Ok(()),
    }
}

/// The bytes of a model argument (a bundled model's; 0 for what is not a
/// file).
fn input_bytes(input: &Path) -> u64 {
    let name = input.to_str().unwrap_or_default();
    match subdiv::bundled::MODELS.iter().find(|m| m.cli_name() == name) {
        Some(m) => m.bytes.len() as u64,
        None => std::fs::metadata(input).map_or(0, |m| if m.is_file() { m.len() } else { 0 }),
    }
}

/// The message of a caught panic.
fn panic_text(panic: &(dyn std::any::Any + Send)) -> String {
    match (panic.downcast_ref::<&str>(), panic.downcast_ref::<String>()) {
        (Some(s), _) => s.to_string(),
        (_, Some(s)) => s.clone(),
        _ => "a panic".into(),
    }
}

/// `m` locked, whether or not a panicking holder poisoned it (every value
/// behind these locks stays whole: counters and handles).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The memory budget of the files in flight.
struct Budget {
    limit: u64,
    used: Mutex<u64>,
    freed: Condvar,
}

impl Budget {
    /// Takes `bytes` (at most the whole budget), waiting until they fit
    /// beside what is held or nothing is held.
    fn take(&self, bytes: u64) -> u64 {
        let bytes = bytes.min(self.limit);
        let mut used = lock(&self.used);
        while *used > 0 && used.saturating_add(bytes) > self.limit {
            used = self.freed.wait(used).unwrap_or_else(PoisonError::into_inner);
        }
        *used += bytes;
        bytes
    }

    /// Gives `bytes` back.
    fn give(&self, bytes: u64) {
        *lock(&self.used) -= bytes;
        self.freed.notify_all();
    }
}

/// Bytes of the budget held by one file, given back when dropped.
struct Held<'a> {
    budget: &'a Budget,
    bytes: u64,
}

impl<'a> Held<'a> {
    /// Waits for `bytes` of `budget` and holds them.
    fn new(budget: &'a Budget, bytes: u64) -> Held<'a> {
        Held { budget, bytes: budget.take(bytes) }
    }

    /// Holds `bytes` instead (giving the old ones back first, then waiting).
    fn resize(&mut self, bytes: u64) {
        self.budget.give(std::mem::take(&mut self.bytes));
        self.bytes = self.budget.take(bytes);
    }
}

impl Drop for Held<'_> {
    fn drop(&mut self) {
        self.budget.give(self.bytes);
    }
}

/// How a run shows its progress: a bar on a terminal, else a line per file
/// on stderr (none with `-q`).
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    tally: Mutex<Tally>,
    todo: usize,
    start: Instant,
}

impl Progress {
    /// Progress over `todo` files, `skipped` others done before.
    fn new(todo: usize, skipped: usize, start: Instant) -> Progress {
        let bar = super::progress::files(todo as u64);
        if skipped > 0 && bar.is_none() && super::logging::warnings_shown() {
            eprintln!("subdiv: {skipped} files done before, skipped");
        }
        Progress { bar, tally: Mutex::new(Tally { skipped, ..Tally::default() }), todo, start }
    }

    /// Counts a finished file and shows it.
    fn finished(&self, r: &Record) {
        let mut t = lock(&self.tally);
        match r.status {
            Status::Done => t.done += 1,
            _ => t.failed += 1,
        }
        t.faces += r.faces.unwrap_or(0) as u64;
        let rate = per_second(t.faces, self.start.elapsed().as_secs_f64());
        let n = t.done + t.failed;
        if let Some(bar) = &self.bar {
            bar.set_message(format!("{} failed, {rate}", t.failed));
            bar.inc(1);
        } else if super::logging::warnings_shown() {
            match &r.error {
                None => eprintln!(
                    "subdiv: [{n}/{}] {} -> {}: {} faces, {:.2} s",
                    self.todo,
                    r.input,
                    r.output,
                    r.faces.unwrap_or(0),
                    r.seconds
                ),
                Some(e) => eprintln!("subdiv: [{n}/{}] {} failed: {e}", self.todo, r.input),
            }
        }
    }

    /// The tally, the bar cleared.
    fn finish(self) -> Tally {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
        self.tally.into_inner().unwrap_or_else(PoisonError::into_inner)
    }
}

/// `faces` over `seconds` as `1.23M faces/s`.
fn per_second(faces: u64, seconds: f64) -> String {
    let rate = faces as f64 / seconds.max(1e-9);
    match rate {
        r if r >= 1e6 => format!("{:.2}M faces/s", r / 1e6),
        r if r >= 1e3 => format!("{:.1}k faces/s", r / 1e3),
        r => format!("{r:.0} faces/s"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A panic in a file's work is caught and named as an internal error;
    /// the budget it held is given back.
    #[test]
    fn a_panic_is_an_internal_error_and_gives_its_memory_back() {
        let budget = Budget { limit: 100, used: Mutex::new(0), freed: Condvar::new() };
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let _held = Held::new(&budget, 60);
            panic!("the refinement broke");
        }));
        let text = panic_text(&*result.unwrap_err());
        assert_eq!(text, "the refinement broke");
        assert_eq!(*lock(&budget.used), 0, "the reservation is given back on unwinding");
        // and the budget admits a whole-budget file again at once
        assert_eq!(Held::new(&budget, 500).bytes, 100);
    }

    /// A file over the budget on every path takes nothing; another takes
    /// its kept peak and the writer's share.
    #[test]
    fn admission_follows_the_librarys_prediction() {
        let d = |peak, least, parts| Demand { peak, least, parts, faces: 0 };
        assert_eq!(admitted(&d(900, 300, 1), 200), 0, "refused by the library at once");
        assert_eq!(admitted(&d(900, 300, 2), 200), 900 + WRITE_BYTES, "a stage's parts wait for the whole budget");
        assert_eq!(admitted(&d(150, 100, 1), 200), 150 + WRITE_BYTES);
    }
}
