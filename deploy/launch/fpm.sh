#!/usr/bin/env bash
# mmh-fpm as a background service: fpm.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-fpm "$@"
