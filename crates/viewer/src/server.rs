//! Serving the routes over TCP with bounds that no client can lift (docs/guide/src/viewer.md):
//! hyper's HTTP/1 connections, each driving the axum router, accepted by [`serve`].
//!
//! - **Header read timeout** (hyper's `header_read_timeout`): a connection whose request
//!   head is not complete within [`Bounds::header_timeout`] is closed; a connection idle
//!   between requests is waiting for its next head, so it is closed after as long.
//! - **Connection cap** ([`Bounds::max_connections`], below the open-file limit): a
//!   connection beyond it closes the oldest *idle* one (no request or response under way:
//!   half-open and keep-alive clients); if every open connection is busy, the new one is
//!   closed. So no number of idle clients locks others out or uses up the file descriptors.
//! - **Shutdown with a deadline**: when `shutdown` resolves, no connection is accepted any
//!   more, every connection is asked to finish (hyper's graceful shutdown: idle ones close
//!   at once, a request under way may complete), and after [`Bounds::shutdown_grace`] the
//!   rest are dropped, whatever their clients do.
//!
//! (A request body is read within [`crate::guard::BODY_TIMEOUT`], by the guard.)

use std::collections::BTreeMap;
use std::future::Future;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::body::Body;
use axum::Router;
use http_body_util::BodyExt;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tokio::task::JoinSet;

/// What bounds the server's connections.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// Longest wait for a request head (also between the requests of a kept-alive connection).
    pub header_timeout: Duration,
    /// Most connections open at once.
    pub max_connections: usize,
    /// How long a shutdown waits for connections to finish before dropping them.
    pub shutdown_grace: Duration,
}

/// Most connections when the open-file limit allows more (a page opens about six).
const MAX_CONNECTIONS: usize = 256;
/// File descriptors kept for everything but connections (the listener, data and texture
/// files read on request, the runtime's own).
const RESERVED_FILES: u64 = 64;
/// The fewest connections, however low the open-file limit.
const MIN_CONNECTIONS: usize = 8;

impl Bounds {
    /// 10 s for a request head, [`MAX_CONNECTIONS`] connections or as many as this
    /// process's open-file limit leaves room for, half a second to shut down.
    pub fn for_this_process() -> Bounds {
        let room = open_file_limit().map_or(MAX_CONNECTIONS, |limit| {
            usize::try_from(limit.saturating_sub(RESERVED_FILES)).unwrap_or(usize::MAX)
        });
        Bounds {
            header_timeout: Duration::from_secs(10),
            max_connections: room.clamp(MIN_CONNECTIONS, MAX_CONNECTIONS),
            shutdown_grace: Duration::from_millis(500),
        }
    }
}

/// The soft limit on this process's open files (`RLIMIT_NOFILE`), if it has one.
fn open_file_limit() -> Option<u64> {
    #[cfg(unix)]
    {
        let mut limit = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit writes the struct it is given and nothing else.
        let read = unsafe { libc::getrlimit(libc::RLIMIT_NOFILE, &mut limit) } == 0;
        (read && limit.rlim_cur != libc::RLIM_INFINITY).then_some(limit.rlim_cur)
    }
    #[cfg(not(unix))]
    None
}

/// An open connection as the accept loop sees it.
struct Open {
    /// Requests (with their responses) under way on it.
    busy: Arc<AtomicUsize>,
    /// Drops the connection.
    abort: tokio::task::AbortHandle,
}

/// Counts a request as under way until dropped (when its response has been sent, or the
/// connection is gone).
struct Busy(Arc<AtomicUsize>);

impl Busy {
    fn enter(count: &Arc<AtomicUsize>) -> Busy {
        count.fetch_add(1, Ordering::SeqCst);
        Busy(count.clone())
    }
}

impl Drop for Busy {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Serves `app` on `listener` within `bounds` until `shutdown` resolves, then shuts down
/// within [`Bounds::shutdown_grace`] (see the module documentation).
pub async fn serve(
    listener: TcpListener,
    app: Router,
    bounds: Bounds,
    shutdown: impl Future<Output = ()>,
) -> std::io::Result<()> {
    // Open connections by age (ids only grow).
    let open: Arc<Mutex<BTreeMap<u64, Open>>> = Arc::default();
    let (stop_tx, stop_rx) = watch::channel(false);
    let mut tasks = JoinSet::new();
    let mut shutdown = std::pin::pin!(shutdown);
    let mut next_id = 0u64;
    loop {
        let (stream, _) = tokio::select! {
            () = &mut shutdown => break,
            accepted = listener.accept() => match accepted {
                Ok(accepted) => accepted,
                Err(_) => {
                    // Out of file descriptors or a connection reset before it was
                    // accepted: try again shortly.
                    tokio::time::sleep(Duration::from_millis(20)).await;
                    continue;
                }
            },
            // Finished connections leave the set as they end.
            Some(_) = tasks.join_next(), if !tasks.is_empty() => continue,
        };
        if !make_room(&open, bounds.max_connections) {
            drop(stream); // every connection is busy: this one is refused
            continue;
        }
        let id = next_id;
        next_id += 1;
        let busy = Arc::new(AtomicUsize::new(0));
        let connection = connection(stream, app.clone(), busy.clone(), bounds, stop_rx.clone());
        let open_in_task = open.clone();
        let abort = tasks.spawn(async move {
            connection.await;
            lock(&open_in_task).remove(&id);
        });
        lock(&open).insert(id, Open { busy, abort });
    }
    drop(listener);
    let _ = stop_tx.send(true);
    let finished = async { while tasks.join_next().await.is_some() {} };
    if tokio::time::timeout(bounds.shutdown_grace, finished)
        .await
        .is_err()
    {
        tasks.abort_all();
    }
    Ok(())
}

fn lock(open: &Mutex<BTreeMap<u64, Open>>) -> std::sync::MutexGuard<'_, BTreeMap<u64, Open>> {
    open.lock().unwrap_or_else(|e| e.into_inner())
}

/// Makes room for one more connection within `max`: drops the oldest idle connections while
/// there are `max` or more; false when all of those are busy.
fn make_room(open: &Mutex<BTreeMap<u64, Open>>, max: usize) -> bool {
    let mut open = lock(open);
    while open.len() >= max {
        let idle = open
            .iter()
            .find(|(_, c)| c.busy.load(Ordering::SeqCst) == 0)
            .map(|(&id, _)| id);
        let Some(id) = idle else {
            return false;
        };
        if let Some(c) = open.remove(&id) {
            c.abort.abort();
        }
    }
    true
}

/// One connection: HTTP/1 with the header read timeout, each request counted as busy until
/// its response body is sent; on `stop`, hyper's graceful shutdown.
async fn connection(
    stream: tokio::net::TcpStream,
    app: Router,
    busy: Arc<AtomicUsize>,
    bounds: Bounds,
    mut stop: watch::Receiver<bool>,
) {
    let routes = TowerToHyperService::new(app);
    let service = hyper::service::service_fn(move |request: hyper::Request<Incoming>| {
        let under_way = Busy::enter(&busy);
        let response = hyper::service::Service::call(&routes, request);
        async move {
            let response = response.await?;
            // The request stays under way while its body is sent.
            Ok::<_, std::convert::Infallible>(response.map(move |body| {
                Body::new(body.map_frame(move |frame| {
                    let _ = &under_way;
                    frame
                }))
            }))
        }
    });
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(bounds.header_timeout);
    let conn = http.serve_connection(TokioIo::new(stream), service);
    let mut conn = std::pin::pin!(conn);
    if *stop.borrow() {
        conn.as_mut().graceful_shutdown();
    }
    loop {
        tokio::select! {
            _ = conn.as_mut() => return,
            changed = stop.changed() => {
                if changed.is_err() || *stop.borrow() {
                    conn.as_mut().graceful_shutdown();
                    // The server's deadline ends what the graceful shutdown does not.
                    let _ = conn.as_mut().await;
                    return;
                }
            }
        }
    }
}
