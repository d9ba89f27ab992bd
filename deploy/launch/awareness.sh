#!/usr/bin/env bash
# mmh-awareness as a background service: awareness.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-awareness "$@"
