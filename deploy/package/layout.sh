# The Debian package's layout, read by service.sh when it runs from /usr/lib/mmh-planner/launch.
mmh_bin_dir=/usr/bin
mmh_config=/etc/mmh/mmh.yaml
mmh_run_dir=/var/lib/mmh
mmh_record=/usr/lib/mmh-planner/record.sh
