"""``tribodyn view --serve``: the page served on this machine only (127.0.0.1), for a
browser that may not open local files. The page is self-contained; the server sends it
and nothing else."""

from __future__ import annotations

from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

__all__ = ["page_server"]


def page_server(page: bytes, port: int = 0) -> ThreadingHTTPServer:
    """An HTTP server on 127.0.0.1:``port`` (0: a free port) answering ``GET /`` (and
    ``/index.html``) with ``page``, 404 otherwise. Start it with ``serve_forever()``."""

    class Handler(BaseHTTPRequestHandler):
        def do_GET(self) -> None:  # the standard library names it so
            if self.path not in ("/", "/index.html"):
                self.send_error(404)
                return
            self.send_response(200)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(page)))
            self.end_headers()
            self.wfile.write(page)

        def log_message(self, format: str, *args) -> None:  # quiet
            return

    return ThreadingHTTPServer(("127.0.0.1", port), Handler)
