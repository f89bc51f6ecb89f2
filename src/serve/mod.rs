//! `netspec serve`: a local web application over the library. It lists the paper's examples and
//! the specs under a root folder, draws a spec with netspec's own renderer and lets the page edit
//! it (every edit checked by the spec code the command line uses), solves it in the background
//! with progress and every improving design streamed to the page (server-sent events), keeps
//! every solve as a run under `ROOT/runs/`, compares runs and exports their files. For real
//! sites it draws OpenStreetMap extracts under the root on a map, makes a site from a box or a
//! polygon drawn there, runs `layout`, `grow`, `city` and `traffic` on it and compares every
//! design with the real streets (`sites`).
//!
//! The server is axum on a tokio runtime of its own; solves run on blocking threads under a
//! semaphore (at most [`ServeOptions::max_solves`] at once, the rest queue) with a thread budget.
//! It serves and writes files only under the root.

mod api;
mod error;
mod runs;
mod sites;
mod specs;

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;

pub use runs::{RunRecord, RunState, Summary};

/// How the server is started (the flags of `netspec serve`).
#[derive(Clone, Debug)]
pub struct ServeOptions {
    /// The folder whose specs are listed and where runs and saved specs go.
    pub root: PathBuf,
    /// The address to listen on (loopback unless told otherwise).
    pub bind: IpAddr,
    /// The port (0: any free port).
    pub port: u16,
    /// Solves running at once; more wait in a queue.
    pub max_solves: usize,
    /// Threads all running solves may use together; each solve gets an equal share.
    pub threads: u32,
    /// The largest request body, bytes.
    pub max_body: usize,
    /// The largest mesh a spec may ask for, cells.
    pub max_cells: usize,
    /// The most solves waiting in the queue.
    pub max_queue: usize,
    /// The `netspec` binary the urban methods of a site run as (`netspec serve` gives its own;
    /// without one a site's methods cannot run).
    pub netspec_bin: Option<PathBuf>,
}

impl Default for ServeOptions {
    fn default() -> Self {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
        ServeOptions {
            root: PathBuf::from("."),
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: 8080,
            max_solves: 2,
            threads: cores,
            max_body: 1 << 20,
            max_cells: 40_000,
            max_queue: 32,
            netspec_bin: None,
        }
    }
}

/// Why the server could not start or stopped.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The root folder is unusable.
    #[error("--root {}: {source}", path.display())]
    Root {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The address could not be bound.
    #[error("listening on {addr}: {source}")]
    Bind {
        /// The address.
        addr: SocketAddr,
        /// The cause.
        source: std::io::Error,
    },
    /// The runtime or the listener failed.
    #[error("serving: {0}")]
    Io(#[from] std::io::Error),
    /// An option is out of range.
    #[error("{0}")]
    Option(String),
}

/// A running server: its address, until it is dropped (which stops it and every solve).
pub struct Server {
    addr: SocketAddr,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    thread: Option<std::thread::JoinHandle<Result<(), std::io::Error>>>,
    app: std::sync::Arc<api::App>,
}

impl Server {
    /// Starts a server on its own threads and returns once it listens.
    pub fn start(opts: ServeOptions) -> Result<Server, ServeError> {
        if opts.max_solves == 0 || opts.threads == 0 {
            return Err(ServeError::Option("--max-solves and --threads must be at least 1".into()));
        }
        let root_err = |source| ServeError::Root { path: opts.root.clone(), source };
        let root = std::fs::canonicalize(&opts.root).map_err(root_err)?;
        if !root.is_dir() {
            return Err(root_err(std::io::Error::new(std::io::ErrorKind::NotADirectory, "not a folder")));
        }
        let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build()?;
        let addr = SocketAddr::new(opts.bind, opts.port);
        let listener =
            rt.block_on(tokio::net::TcpListener::bind(addr)).map_err(|source| ServeError::Bind { addr, source })?;
        let addr = listener.local_addr()?;
        let app = std::sync::Arc::new(api::App::new(root, &opts).map_err(root_err)?);
        let router = api::router(app.clone(), opts.max_body);
        let (tx, rx) = tokio::sync::oneshot::channel::<()>();
        let thread = std::thread::Builder::new().name("netspec-serve".into()).spawn(move || {
            let served = rt.block_on(async move {
                tokio::select! {
                    r = axum::serve(listener, router) => r,
                    _ = rx => Ok(()),
                }
            });
            // Open event streams and solves still running must not hold the process.
            rt.shutdown_background();
            served
        })?;
        Ok(Server { addr, stop: Some(tx), thread: Some(thread), app })
    }

    /// The address the server listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Blocks until the server stops (it stops on an I/O error of its listener).
    pub fn wait(mut self) -> Result<(), ServeError> {
        match self.thread.take().map(|t| t.join()) {
            Some(Ok(r)) => Ok(r?),
            Some(Err(_)) => Err(ServeError::Option("the server thread panicked".into())),
            None => Ok(()),
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.app.stop_all();
        if let Some(tx) = self.stop.take() {
            let _ = tx.send(());
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// `netspec serve`: starts the server, tells `ready` its address, and serves until the process
/// ends.
pub fn run(opts: ServeOptions, ready: impl FnOnce(SocketAddr)) -> Result<(), ServeError> {
    let server = Server::start(opts)?;
    ready(server.addr());
    server.wait()
}
