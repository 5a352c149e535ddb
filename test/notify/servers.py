#!/usr/bin/env python3
"""Real servers for the notifier's tests, on loopback (issue 44): an SMTP server (Debian's
python3-aiosmtpd) and an HTTP webhook receiver (python3's http.server). Each message received is
appended to LOG as one JSON line and fsync'd before the server acknowledges it, so the log is what
the server accepted. Prints "ready PORT" when it listens.

  servers.py smtp|http PORT LOG [--die-at N] [--reject TEXT] [--fail-first K]
             [--starttls CERT KEY] [--smtps CERT KEY] [--login USER:PASSWORD] [--tls CERT KEY]

--die-at N      the N-th message (counting from 1 over this process's life) kills the server before
                it is stored or acknowledged: a crash in the middle of a delivery
--reject TEXT   SMTP: refuse every recipient containing TEXT with 550 (a permanent error with a reason)
--fail-first K  HTTP: answer the first K POSTs with 503 and a reason in the body
--starttls      SMTP: require STARTTLS with this certificate and key before anything else
--smtps         SMTP: TLS from the first byte (smtps://) with this certificate and key
--login         SMTP: require AUTH (LOGIN or PLAIN) with this user and password (after STARTTLS)
--tls           HTTP: HTTPS with this certificate and key (a webhook over TLS)
"""
import argparse
import email
import email.policy
import json
import os
import signal
import sys
import time


def append(log, record):
    record['received'] = time.time()  # s since 1970: the tests measure latency with it
    with open(log, 'a', encoding='utf-8') as f:
        f.write(json.dumps(record) + '\n')
        f.flush()
        os.fsync(f.fileno())


def main():
    p = argparse.ArgumentParser()
    p.add_argument('kind', choices=['smtp', 'http'])
    p.add_argument('port', type=int)
    p.add_argument('log')
    p.add_argument('--die-at', type=int, default=0)
    p.add_argument('--reject', default='')
    p.add_argument('--fail-first', type=int, default=0)
    p.add_argument('--starttls', nargs=2, metavar=('CERT', 'KEY'))
    p.add_argument('--login', default='')
    p.add_argument('--tls', nargs=2, metavar=('CERT', 'KEY'))
    p.add_argument('--smtps', nargs=2, metavar=('CERT', 'KEY'))
    a = p.parse_args()
    seen = [0]

    def arrived():
        seen[0] += 1
        if a.die_at and seen[0] == a.die_at:
            os._exit(9)  # killed mid-delivery: nothing stored, nothing acknowledged

    if a.kind == 'smtp':
        from aiosmtpd.controller import Controller

        class Handler:
            async def handle_RCPT(self, server, session, envelope, address, rcpt_options):
                if a.reject and a.reject in address:
                    return f'550 5.1.1 <{address}>: Recipient address rejected: User unknown'
                envelope.rcpt_tos.append(address)
                return '250 OK'

            async def handle_DATA(self, server, session, envelope):
                arrived()
                msg = email.message_from_bytes(envelope.content, policy=email.policy.default)
                append(a.log, {'id': msg['Message-ID'], 'to': envelope.rcpt_tos, 'from': envelope.mail_from,
                               'subject': str(msg['Subject']), 'body': msg.get_content(),
                               'headers': list(msg.keys()), 'content_type': msg.get_content_type(),
                               'tls': session.ssl is not None or server.transport.get_extra_info('ssl_object') is not None, 'authenticated': bool(session.authenticated)})
                return '250 OK queued'

        options = {}
        if a.starttls:
            import ssl
            context = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
            context.load_cert_chain(*a.starttls)
            options.update(tls_context=context, require_starttls=True)
        if a.smtps:  # TLS from the first byte (smtps://, port 465's way), no STARTTLS
            import ssl
            context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
            context.load_cert_chain(*a.smtps)
            options.update(ssl_context=context)
        if a.login:
            from aiosmtpd.smtp import AuthResult
            user, password = a.login.split(':', 1)

            def authenticator(server, session, envelope, mechanism, auth_data):
                ok = auth_data.login.decode() == user and auth_data.password.decode() == password
                return AuthResult(success=ok, handled=False)
            options.update(authenticator=authenticator, auth_required=True, auth_require_tls=bool(a.starttls))
        controller = Controller(Handler(), hostname='127.0.0.1', port=a.port, **options)
        controller.start()
        print('ready', a.port, flush=True)
        signal.sigwait({signal.SIGTERM, signal.SIGINT})
        controller.stop()
        return

    from http.server import BaseHTTPRequestHandler, HTTPServer

    class Hook(BaseHTTPRequestHandler):
        def do_POST(self):
            body = self.rfile.read(int(self.headers.get('Content-Length', 0)))
            arrived()
            if seen[0] <= a.fail_first:
                reply = b'receiver in maintenance'
                self.send_response(503)
                self.send_header('Content-Length', str(len(reply)))
                self.end_headers()
                self.wfile.write(reply)
                return
            doc = json.loads(body)
            append(a.log, {'id': self.headers.get('Idempotency-Key'), 'path': self.path, 'subject': doc['subject'],
                           'recipient': doc['recipient'], 'counts': doc['counts'],
                           'alarms': [{'item': x['item'], 'level': x['level']} for x in doc['alarms']]})
            self.send_response(200)
            self.send_header('Content-Length', '2')
            self.end_headers()
            self.wfile.write(b'ok')

        def log_message(self, *args):
            pass

    HTTPServer.allow_reuse_address = True
    server = HTTPServer(('127.0.0.1', a.port), Hook)
    if a.tls:
        import ssl
        context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
        context.load_cert_chain(*a.tls)
        server.socket = context.wrap_socket(server.socket, server_side=True)
    print('ready', a.port, flush=True)
    server.serve_forever()


if __name__ == '__main__':
    sys.exit(main())
