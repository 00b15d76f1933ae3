//! The server's bounds on connections (`viewer::server`, issue 24: 1100 half-open connections
//! made `godel view` unreachable and none was closed after 40 s; while a client held a
//! half-sent request, Ctrl-C and SIGTERM did not stop the server): a request head must come
//! within the header timeout, a connection beyond the cap closes the oldest idle one (never a
//! busy one), and a shutdown ends within its deadline whatever the clients do.
//!
//! Each test runs the real server on a port of its own; the clients are plain TCP sockets.
//! The read timeouts are deadlines against hanging forever, not speed checks.

use crate::common;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::mpsc;
use std::time::Duration;

use viewer::server::{serve, Bounds};
use viewer::Access;

/// A deadline against hanging forever.
const DEADLINE: Duration = Duration::from_secs(60);

/// The server on a free port, in a thread of its own; dropping it shuts the server down.
struct Running {
    port: u16,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    /// Says when `serve` has returned.
    ended: mpsc::Receiver<()>,
}

impl Running {
    fn start(bounds: Bounds) -> Running {
        let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        listener.set_nonblocking(true).unwrap();
        let addr = listener.local_addr().unwrap();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let (done, ended) = mpsc::channel();
        std::thread::spawn(move || {
            let runtime = tokio::runtime::Builder::new_multi_thread()
                .worker_threads(2)
                .enable_all()
                .build()
                .unwrap();
            runtime.block_on(async move {
                let listener = tokio::net::TcpListener::from_std(listener).unwrap();
                let app = viewer::router(common::state(), Access::listening_on(addr));
                let shutdown = async {
                    let _ = stopped.await;
                };
                serve(listener, app, bounds, shutdown).await.unwrap();
            });
            let _ = done.send(());
            runtime.shutdown_timeout(Duration::from_millis(100));
        });
        Running {
            port: addr.port(),
            stop: Some(stop),
            ended,
        }
    }

    fn connect(&self) -> TcpStream {
        let stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.set_read_timeout(Some(DEADLINE)).unwrap();
        stream
    }

    /// Shuts the server down; true when `serve` returned before the deadline.
    fn shut_down(&mut self) -> bool {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        self.ended.recv_timeout(DEADLINE).is_ok()
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
    }
}

/// Reads until the server closes the connection (or the deadline passes: then it panics);
/// returns what was read.
fn read_to_close(stream: &mut TcpStream) -> String {
    let mut answer = Vec::new();
    match stream.read_to_end(&mut answer) {
        Ok(_) => {}
        Err(e) if e.kind() == std::io::ErrorKind::ConnectionReset => {}
        Err(e) => panic!("the server did not close the connection: {e}"),
    }
    String::from_utf8_lossy(&answer).into_owned()
}

fn bounds(header_timeout: Duration, max_connections: usize) -> Bounds {
    Bounds {
        header_timeout,
        max_connections,
        shutdown_grace: Duration::from_millis(500),
    }
}

fn get_info(port: u16) -> String {
    format!("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n")
}

#[test]
fn a_request_head_that_never_ends_is_closed() {
    let server = Running::start(bounds(Duration::from_millis(300), 64));
    let mut half = server.connect();
    half.write_all(b"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1")
        .unwrap();
    let mut idle = server.connect();
    read_to_close(&mut half);
    read_to_close(&mut idle);
    // The server still answers.
    let mut fresh = server.connect();
    fresh.write_all(get_info(server.port).as_bytes()).unwrap();
    assert!(read_to_close(&mut fresh).starts_with("HTTP/1.1 200"));
}

#[test]
fn beyond_the_cap_the_oldest_idle_connection_is_closed_never_a_busy_one() {
    let server = Running::start(bounds(DEADLINE, 3));
    let port = server.port;
    // Busy: a request whose body is still coming. hyper says `100 Continue` once the route
    // reads the body: from then on the request is under way.
    let mut busy = server.connect();
    let head = format!(
        "POST /api/keyframe HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\
         Content-Type: application/json\r\nContent-Length: 2\r\nExpect: 100-continue\r\n\
         Connection: close\r\n\r\n"
    );
    busy.write_all(head.as_bytes()).unwrap();
    let mut continuing = [0u8; 25];
    busy.read_exact(&mut continuing).unwrap();
    assert_eq!(&continuing, b"HTTP/1.1 100 Continue\r\n\r\n");
    busy.write_all(b"{").unwrap();
    // Idle: connected, nothing sent (accepted in the order they connect).
    let mut oldest = server.connect();
    let mut older = server.connect();
    // Each new connection beyond three closes the oldest idle one.
    let mut newer = server.connect();
    assert_eq!(read_to_close(&mut oldest), "");
    let mut newest = server.connect();
    assert_eq!(read_to_close(&mut older), "");
    // The newer ones are served, and so is the busy request once its body is complete.
    newer.write_all(get_info(port).as_bytes()).unwrap();
    assert!(read_to_close(&mut newer).starts_with("HTTP/1.1 200"));
    busy.write_all(b"}").unwrap();
    let answer = read_to_close(&mut busy);
    assert!(answer.starts_with("HTTP/1.1 "), "{answer:?}");
    newest.write_all(get_info(port).as_bytes()).unwrap();
    assert!(read_to_close(&mut newest).starts_with("HTTP/1.1 200"));
}

#[test]
fn a_shutdown_ends_within_its_deadline_whatever_the_clients_do() {
    let mut server = Running::start(bounds(DEADLINE, 64));
    let port = server.port;
    let mut half = server.connect();
    half.write_all(b"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1")
        .unwrap();
    let mut body = server.connect();
    let head = format!(
        "POST /api/png HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\
         Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{{\"shaders\""
    );
    body.write_all(head.as_bytes()).unwrap();
    let mut kept_alive = server.connect();
    kept_alive
        .write_all(format!("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n").as_bytes())
        .unwrap();
    let mut status = [0u8; 12];
    kept_alive.read_exact(&mut status).unwrap();
    assert_eq!(&status, b"HTTP/1.1 200");
    std::thread::sleep(Duration::from_millis(100));
    assert!(
        server.shut_down(),
        "serve did not return after the shutdown"
    );
    for stream in [&mut half, &mut body, &mut kept_alive] {
        read_to_close(stream);
    }
}
