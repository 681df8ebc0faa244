"""The meshcat server process, bound to 127.0.0.1 only.

meshcat 0.3's ``zmqserver`` serves its web page with ``tornado.web.Application.listen(port)``,
which listens on every interface. This entry point pins tornado's listen address to the loopback
interface, then runs meshcat's own server unchanged. Started by :mod:`afmsmiler.scenes.viewer`
as ``python -m afmsmiler.scenes._server``.
"""
import tornado.web

LOOPBACK = "127.0.0.1"
_listen = tornado.web.Application.listen


def _listen_on_loopback(self, port, address=None, **kwargs):
    return _listen(self, port, address=LOOPBACK, **kwargs)


def main():
    tornado.web.Application.listen = _listen_on_loopback
    from meshcat.servers.zmqserver import main as meshcat_main
    meshcat_main()


if __name__ == "__main__":
    main()
