#!/usr/bin/env bash
# mmh-arbiter as a background service: arbiter.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-arbiter "$@"
