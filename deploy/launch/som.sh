#!/usr/bin/env bash
# mmh-som as a background service: som.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-som "$@"
