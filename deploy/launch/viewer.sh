#!/usr/bin/env bash
# mmh-viewer (the ground station in the browser) as a background service:
# viewer.sh start|stop|restart|status|run [options] [-- --bind ADDR:PORT]
# (options and environment: see service.sh; docs/viewer.md)
exec "$(dirname "$0")/service.sh" mmh-viewer "$@"
