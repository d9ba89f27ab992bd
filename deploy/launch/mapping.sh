#!/usr/bin/env bash
# mmh-mapping as a background service: mapping.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-mapping "$@"
