#!/bin/sh
# run_in_xvfb.sh SCREEN COMMAND [ARGS...]: COMMAND in a fresh Xvfb server (SCREEN as WxHxD); exits with
# COMMAND's own status. xvfb-run's cleanup can fail after the command has finished ("problem while cleaning up
# temporary directory", status 5) when Xvfb runs overlap under load; that must not fail a test the command passed.
screen=$1
shift
status_file=$(mktemp)
xvfb-run -a -s "-screen 0 $screen" sh -c '"$@"; echo $? >"$0"' "$status_file" "$@"
xvfb_status=$?
status=$(cat "$status_file" 2>/dev/null)
rm -f "$status_file"
if [ -n "$status" ]; then exit "$status"; fi
exit "$xvfb_status"
