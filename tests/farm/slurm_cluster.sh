# A real one-node Slurm cluster for the farm tests, sourced by them:
# `start_cluster SCRATCH` installs Debian's slurm-wlm, slurmdbd, munge and
# mariadb-server when missing, writes a slurm.conf and slurmdbd.conf for
# localhost (this machine's CPUs, free ports, every database, state, spool,
# log and socket file under SCRATCH), starts munged, a private MariaDB (on
# 127.0.0.1 and a free port, never the system's), slurmdbd, slurmctld and
# slurmd as this shell's own processes and waits until the node is idle. An
# EXIT trap stops them by PID whatever happens. Nothing outside this machine
# is contacted. Needs root (SlurmUser=root), as CI machines give.
#
# After start_cluster: SLURM_CONF is exported for sbatch, squeue, scontrol,
# scancel and sacct; the helpers below wait on jobs and read their final
# states.

cluster_pids=()
stop_cluster() {
  local pid
  # Cancel what is left, so that no job process outlives the test.
  if [ -n "${SLURM_CONF:-}" ] && [ ${#cluster_pids[@]} -gt 0 ]; then
    local jobs
    jobs=$(timeout 10 squeue -h -o '%A' 2> /dev/null | sort -u | tr '\n' ' ' || true)
    if [ -n "${jobs// /}" ]; then
      # shellcheck disable=SC2086
      timeout 10 scancel $jobs 2> /dev/null || true
      for _ in $(seq 100); do [ -z "$(timeout 5 squeue -h 2> /dev/null)" ] && break; sleep 0.1; done
    fi
  fi
  # Last started, first stopped: slurmd and slurmctld before slurmdbd, which
  # writes their last records to MariaDB, stopped before munged.
  local i
  for ((i = ${#cluster_pids[@]} - 1; i >= 0; i--)); do
    pid=${cluster_pids[i]}
    kill "$pid" 2> /dev/null || continue
    for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2> /dev/null || true
  done
  cluster_pids=()
  # A job's slurmstepd outlives slurmd: stop this cluster's own, by PID.
  kill_job_processes
}
trap stop_cluster EXIT

cluster_fail() { echo "FAILED: $*" >&2; cluster_logs >&2; exit 1; }
cluster_logs() {
  local log
  for log in "$cluster_dir"/log/*.log; do echo "--- $log"; tail -n 20 "$log"; done
}

# Installs slurm-wlm, slurmdbd, munge and mariadb-server with apt-get when a
# binary is missing.
install_slurm() {
  local missing=0 tool
  for tool in munged mungekey slurmctld slurmd slurmdbd sbatch scontrol squeue scancel sacct sacctmgr \
    mariadbd mariadb-install-db mariadb; do
    command -v "$tool" > /dev/null 2>&1 || [ -x "/usr/sbin/$tool" ] || missing=1
  done
  [ "$missing" -eq 0 ] && return 0
  [ "$(id -u)" -eq 0 ] || { echo "SKIPPED: the Slurm tests install slurm-wlm and need root" >&2; exit 77; }
  echo "slurm test: installing slurm-wlm, slurmdbd, munge and mariadb-server" >&2
  apt-get update -q > /dev/null
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
    slurm-wlm slurmdbd munge mariadb-server > /dev/null
}

free_port() {  # a TCP port nothing listens on now
  /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

start_cluster() {
  cluster_dir=$1
  install_slurm
  export PATH="$PATH:/usr/sbin"
  [ "$(id -u)" -eq 0 ] || { echo "SKIPPED: the Slurm tests run slurmd as root" >&2; exit 77; }
  rm -rf "$cluster_dir"
  mkdir -p "$cluster_dir"/{munge,run,state,spool,log}
  # munged refuses a key others may read and a socket folder others may
  # write to or cannot enter.
  chmod 755 "$cluster_dir" "$cluster_dir/run"
  chmod 700 "$cluster_dir/munge"
  local ctld_port slurmd_port dbd_port db_port
  ctld_port=$(free_port) slurmd_port=$(free_port) dbd_port=$(free_port) db_port=$(free_port)
  while [ "$(printf '%s\n' "$ctld_port" "$slurmd_port" "$dbd_port" "$db_port" | sort -u | grep -c .)" -ne 4 ]; do
    slurmd_port=$(free_port) dbd_port=$(free_port) db_port=$(free_port)
  done
  write_slurm_conf "$ctld_port" "$slurmd_port" "$dbd_port"
  mungekey --create --keyfile="$cluster_dir/munge/munge.key" --force > /dev/null
  chmod 600 "$cluster_dir/munge/munge.key"
  munged --foreground --socket="$cluster_dir/run/munge.socket" --key-file="$cluster_dir/munge/munge.key" \
    --pid-file="$cluster_dir/munge/munged.pid" --log-file="$cluster_dir/log/munged.log" \
    --seed-file="$cluster_dir/munge/munged.seed" > "$cluster_dir/log/munged.out" 2>&1 &
  cluster_pids+=($!)
  for _ in $(seq 50); do [ -S "$cluster_dir/run/munge.socket" ] && break; sleep 0.1; done
  [ -S "$cluster_dir/run/munge.socket" ] || cluster_fail "munged did not start"
  start_accounting "$dbd_port" "$db_port" "aaftest$ctld_port"
  slurmctld -D -i -f "$SLURM_CONF" > "$cluster_dir/log/slurmctld.out" 2>&1 &
  cluster_pids+=($!)
  start_slurmd
  wait_node_idle
}

# write_slurm_conf CTLD_PORT SLURMD_PORT DBD_PORT: SCRATCH/slurm.conf for
# localhost, SLURM_CONF exported.
write_slurm_conf() {
  local ctld_port=$1 slurmd_port=$2 dbd_port=$3 cpus memory_mb
  cpus=$(nproc)
  memory_mb=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2))
  cat > "$cluster_dir/slurm.conf" << EOF
ClusterName=aaftest$ctld_port
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$cluster_dir/run/munge.socket
StateSaveLocation=$cluster_dir/state
SlurmdSpoolDir=$cluster_dir/spool
SlurmctldPidFile=$cluster_dir/slurmctld.pid
SlurmdPidFile=$cluster_dir/slurmd.pid
SlurmctldLogFile=$cluster_dir/log/slurmctld.log
SlurmdLogFile=$cluster_dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
# The main scheduler runs every second (default 60 s): a requeued task
# whose start time has come starts without waiting.
SchedulerParameters=sched_interval=1
# Every job and array task is recorded by slurmdbd (for sacct).
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=localhost
AccountingStoragePort=$dbd_port
# The munge socket for every connection to slurmdbd (slurmctld's, sacct's,
# sacctmgr's): AuthInfo covers only the other messages.
AccountingStoragePass=$cluster_dir/run/munge.socket
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$cluster_dir/log/jobcomp.txt
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
# A batch job the node no longer runs when it registers again is taken for
# lost (and requeued) once it has run BatchStartTimeout + MessageTimeout.
BatchStartTimeout=2
MessageTimeout=5
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=farm Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$cluster_dir/slurm.conf"
}

# A private MariaDB (its data, socket and PID file under SCRATCH/db, TCP on
# 127.0.0.1:DB_PORT only, as slurmdbd reaches it) and slurmdbd on DBD_PORT,
# with the cluster NAME registered.
start_accounting() {
  local dbd_port=$1 db_port=$2 name=$3 db=$cluster_dir/db password
  mkdir -p "$db"
  mariadb-install-db --no-defaults --user=root --datadir="$db/data" --auth-root-authentication-method=normal \
    --skip-test-db > "$cluster_dir/log/mariadb-install-db.out" 2>&1 \
    || { tail -n 20 "$cluster_dir/log/mariadb-install-db.out" >&2; cluster_fail "mariadb-install-db failed"; }
  # No durability wanted for a test database: the log is not flushed per
  # commit. The lock wait is slurmdbd's recommendation; its warning about the
  # buffer pool (it wants half the machine's memory) is expected.
  mariadbd --no-defaults --user=root --datadir="$db/data" --socket="$db/mysqld.sock" --pid-file="$db/mysqld.pid" \
    --bind-address=127.0.0.1 --port="$db_port" --skip-name-resolve --log-error="$cluster_dir/log/mariadb.log" \
    --innodb-flush-log-at-trx-commit=0 --innodb-lock-wait-timeout=900 \
    > "$cluster_dir/log/mariadb.out" 2>&1 &
  cluster_pids+=($!)
  cluster_sql() { mariadb --no-defaults --socket="$db/mysqld.sock" -u root "$@"; }
  for _ in $(seq 100); do cluster_sql -e 'SELECT 1' > /dev/null 2>&1 && break; sleep 0.1; done
  password=$(od -An -N12 -tx1 /dev/urandom | tr -d ' \n')
  cluster_sql -e "CREATE DATABASE slurm_acct_db; CREATE USER 'slurm'@'127.0.0.1' IDENTIFIED BY '$password';
    GRANT ALL ON slurm_acct_db.* TO 'slurm'@'127.0.0.1';" 2>> "$cluster_dir/log/mariadb.log" \
    || cluster_fail "the private MariaDB did not start"
  # slurmdbd refuses a configuration file others may read.
  (umask 077 && cat > "$cluster_dir/slurmdbd.conf") << EOF
DbdHost=localhost
DbdPort=$dbd_port
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$cluster_dir/run/munge.socket
PidFile=$cluster_dir/slurmdbd.pid
LogFile=$cluster_dir/log/slurmdbd.log
DebugLevel=info
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort=$db_port
StorageUser=slurm
StoragePass=$password
StorageLoc=slurm_acct_db
EOF
  chmod 600 "$cluster_dir/slurmdbd.conf"
  # slurmdbd reads the slurmdbd.conf beside SLURM_CONF's slurm.conf.
  slurmdbd -D > "$cluster_dir/log/slurmdbd.out" 2>&1 &
  local dbd_pid=$! added=0 deadline=$((SECONDS + 30))
  cluster_pids+=("$dbd_pid")
  while [ "$SECONDS" -lt "$deadline" ]; do
    kill -0 "$dbd_pid" 2> /dev/null || { cat "$cluster_dir/log/slurmdbd.out" >&2; cluster_fail "slurmdbd exited"; }
    timeout 5 sacctmgr -i add cluster "$name" > "$cluster_dir/log/sacctmgr.log" 2>&1 && { added=1; break; }
    sleep 0.2
  done
  [ "$added" -eq 1 ] || cluster_fail "slurmdbd did not start or refused the cluster $name"
}

start_slurmd() {
  slurmd -D -N localhost -f "$SLURM_CONF" > "$cluster_dir/log/slurmd.out" 2>&1 &
  slurmd_pid=$!
  cluster_pids+=($slurmd_pid)
}

stop_slurmd() {  # stops the node's daemon the way a failing node loses it
  kill -KILL "$slurmd_pid"
  wait "$slurmd_pid" 2> /dev/null || true
}

# The PIDs of this cluster's job processes: its slurmstepd (started by its
# slurmd, so they carry its SLURM_CONF) and all their descendants.
job_processes() {
  local proc pid parent
  declare -A parent_of=()
  local roots=()
  for proc in /proc/[0-9]*; do
    pid=${proc#/proc/}
    parent=$(awk '{print $4}' "$proc/stat" 2> /dev/null) || continue
    parent_of[$pid]=$parent
    [ "$(cat "$proc/comm" 2> /dev/null)" = slurmstepd ] || continue
    grep -qxF "SLURM_CONF=${SLURM_CONF:-none}" <<< "$({ tr '\0' '\n' < "$proc/environ"; } 2> /dev/null)" && roots+=("$pid")
  done
  local found=("${roots[@]}") grew=1
  while [ "$grew" -eq 1 ]; do
    grew=0
    for pid in "${!parent_of[@]}"; do
      [[ " ${found[*]} " == *" $pid "* ]] && continue
      if [[ " ${found[*]} " == *" ${parent_of[$pid]} "* ]]; then found+=("$pid"); grew=1; fi
    done
  done
  echo "${found[@]}"
}

task_processes() {  # task_processes ARRAY_JOB TASK: the PIDs of that array task's own processes
  local pid
  for pid in $(job_processes); do
    [ "$(cat "/proc/$pid/comm" 2> /dev/null)" != slurmstepd ] || continue
    { tr '\0' '\n' < "/proc/$pid/environ"; } 2> /dev/null \
      | grep -xF -e "SLURM_ARRAY_JOB_ID=$1" -e "SLURM_ARRAY_TASK_ID=$2" | grep -c . | grep -qx 2 && echo "$pid"
  done
  return 0  # not the last process's test
}

kill_job_processes() {  # as a node that loses power: every job process dies at once
  local pids
  pids=$(job_processes)
  # shellcheck disable=SC2086
  [ -z "$pids" ] || kill -KILL $pids 2> /dev/null || true
}

wait_node_idle() {
  local state=
  for _ in $(seq 300); do
    state=$(sinfo -h -n localhost -o '%T' 2> /dev/null || true)
    case $state in idle | mixed | allocated) return 0 ;; esac
    sleep 0.1
  done
  cluster_fail "the node is not idle (state '$state')"
}

# The state of each task of job JOB, one "JOBID_TASK STATE EXIT" line each,
# from the controller.
job_states() {
  scontrol show job -o "$1" | sed -n 's/.*JobId=\([0-9]*\) ArrayJobId=\([0-9]*\) ArrayTaskId=\([0-9]*\) .*JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\) .*/\2_\3 \4 \5/p' | sort -t_ -k2 -n
}

wait_job() {  # wait_job JOB SECONDS: until no task of JOB is pending or running
  local job=$1 limit=$2 waited=0
  while [ -n "$(squeue -h -j "$job" -o '%T' 2> /dev/null)" ]; do
    sleep 0.5
    waited=$((waited + 1))
    [ "$waited" -le $((limit * 2)) ] || { job_states "$job"; cluster_fail "job $job still running after ${limit}s"; }
  done
}

expect_completed() {  # expect_completed JOB TASKS: that many tasks, every one COMPLETED with exit 0:0
  local job=$1 tasks=$2 states
  states=$(job_states "$job")
  [ "$(grep -c . <<< "$states")" -eq "$tasks" ] || { echo "$states"; cluster_fail "job $job has not $tasks tasks"; }
  if grep -v ' COMPLETED 0:0$' <<< "$states"; then cluster_fail "a task of job $job did not complete"; fi
  # The completion log (JobCompType=jobcomp/filetxt) says the same.
  local done
  done=$(grep -c "JobId=[0-9]* .*JobState=COMPLETED" "$cluster_dir/log/jobcomp.txt" || true)
  [ "$done" -ge "$tasks" ] || cluster_fail "the completion log has $done COMPLETED tasks, expected $tasks or more"
}

# expect_accounted JOB TASKS: sacct (the accounting database, through
# slurmdbd) lists tasks JOB_0 to JOB_(TASKS-1), every one COMPLETED. The
# controller sends its records on, so they may arrive a few seconds late.
expect_accounted() {
  local job=$1 tasks=$2 expected accounted=
  expected=$(for task in $(seq 0 $((tasks - 1))); do echo "${job}_$task|COMPLETED"; done)
  for _ in $(seq 40); do
    accounted=$(sacct -X -n -P -j "$job" --format=JobID,State 2> /dev/null | sort -t_ -k2 -n || true)
    [ "$accounted" = "$expected" ] && return 0
    sleep 0.5
  done
  cluster_fail "sacct does not list the $tasks tasks of job $job COMPLETED: it lists '$(paste -sd ' ' <<< "$accounted")'"
}
