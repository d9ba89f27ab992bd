#!/usr/bin/env bash
# mmh-eam as a background service: eam.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-eam "$@"
