#!/usr/bin/env bash
# lcm-logger as a service: records the vehicle's channels (see service.sh, NAME mmh-logger).
exec "$(dirname "$0")/service.sh" mmh-logger "$@"
