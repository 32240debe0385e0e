//! `rope run --web`: the web viewer's page and its files are served while the run streams.
//! (The page in a real browser is `scripts/web-check.py`, which CI runs.)

mod common;

use common::cli::{signal_and_wait, start, stderr_lines_until};
use std::io::{Read as _, Write as _};
use std::time::Duration;

/// The status line and headers of `GET path` from `127.0.0.1:port`, and the body's length.
fn get(port: u16, path: &str) -> (String, usize) {
    let mut stream = std::net::TcpStream::connect(("127.0.0.1", port)).expect("the page server");
    stream
        .set_read_timeout(Some(Duration::from_secs(20)))
        .unwrap();
    write!(
        stream,
        "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut response = Vec::new();
    stream.read_to_end(&mut response).expect("a response");
    let split = response
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("headers end");
    let head = String::from_utf8_lossy(&response[..split]).to_lowercase();
    (head, response.len() - split - 4)
}

#[test]
fn the_web_viewer_page_and_its_wasm_are_served_while_the_run_streams() {
    let (web, grpc) = (common::cli::free_port(), common::cli::free_pair());
    let mut run = start(&[
        "run",
        "--web",
        &format!("127.0.0.1:{web}"),
        "--serve-grpc",
        &format!("127.0.0.1:{grpc}"),
        "--no-browser",
        "--duration",
        "inf",
        "--realtime",
    ]);
    let said = stderr_lines_until(&mut run, "watch it in a browser at");
    let page = said.expect("the page's address is printed");
    assert!(
        page.contains(&format!(
            "http://127.0.0.1:{web}/?url=rerun%2Bhttp%3A%2F%2F127.0.0.1%3A{grpc}%2Fproxy"
        )),
        "{page}"
    );
    let (head, body) = get(web, "/");
    assert!(
        head.starts_with("http/1.1 200") && head.contains("content-type: text/html"),
        "{head}"
    );
    assert!(body > 1000, "an HTML page, {body} bytes");
    let (head, body) = get(web, "/re_viewer_bg.wasm");
    assert!(head.contains("content-type: application/wasm"), "{head}");
    assert!(body > 10_000_000, "the built viewer, {body} bytes");
    let (status, _) = signal_and_wait(&mut run, "-TERM", Duration::from_secs(10));
    assert_eq!(status.code(), Some(130));
}

#[test]
fn a_web_address_already_taken_is_refused_naming_it() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let grpc = common::cli::free_pair();
    let out = common::cli::rope(&[
        "run",
        "--web",
        &format!("127.0.0.1:{port}"),
        "--serve-grpc",
        &format!("127.0.0.1:{grpc}"),
        "--no-browser",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("web = 127.0.0.1:{port}")),
        "{stderr}"
    );
}
