/* cli_tree.c - what the host tool finds beside itself: files of its source
 * tree (configs/, tools/) and a Python 3 interpreter with the modules a
 * script needs (tune: numpy, scipy, matplotlib; replay --plot: numpy,
 * matplotlib). No interpreter path is built in: $HEXAGLIDE_PYTHON, else
 * every python3 on $PATH, each checked by importing the modules. And the
 * output files: a regular file (or a new one) through a temporary file and
 * a rename, a symlink's target the same way, a FIFO or device straight. */
#define _GNU_SOURCE                    /* fopencookie: stdout keeping its write error (cli_stdout_init) */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "cli.h"

#define PY_TRIED_MAX 16        /* interpreters reported in the failure message */

/* The directory of this executable into dir (PATH_MAX); 0 or -1. */
static int exe_dir(char *dir)
{
    char *slash;
    ssize_t n = readlink("/proc/self/exe", dir, PATH_MAX - 1);
    if (n <= 0)
        return -1;
    dir[n] = '\0';
    slash = strrchr(dir, '/');          /* .../build/hexaglide -> .../build */
    if (!slash)
        return -1;
    *slash = '\0';
    return 0;
}

int cli_beside_path(const char *name, char *out, size_t len)
{
    char dir[PATH_MAX];
    if (exe_dir(dir))
        return -1;
    return snprintf(out, len, "%s/%s", dir, name) < (int)len ? 0 : -1;
}

int cli_tree_path(const char *rel, char *out, size_t len)
{
    char dir[PATH_MAX], first[PATH_MAX + 256];
    int up;
    if (exe_dir(dir))
        return -1;
    for (up = 0; up < 2; up++) {       /* build/hexaglide, build/asan/hexaglide */
        char *slash = strrchr(dir, '/');
        if (!slash)
            break;
        *slash = '\0';
        if (snprintf(out, len, "%s/%s", dir, rel) >= (int)len)
            return -1;
        if (up == 0)
            snprintf(first, sizeof first, "%s", out);
        if (access(out, F_OK) == 0)
            return 0;
    }
    if (up > 0)                        /* not found: out names the first place looked */
        snprintf(out, len, "%s", first);
    return -1;
}

/* Run `python -c "import a, b"` for the modules; 0 if it imports them, else
 * -1 with the last line of what it printed (or why it did not run) in why. */
#define PY_PROBE_STATUS 42              /* the probe's exit status when the imports worked */
static int python_imports(const char *python, const char *modules, char *why, size_t len)
{
    char code[256], buf[4096];
    size_t used = 0, i, j;
    int fd[2], status = 0;
    ssize_t got;
    pid_t pid;
    for (i = 0, j = 0; modules[i] && j + 3 < sizeof code; i++) {   /* "a b" -> "import a, b" */
        if (j == 0) {
            memcpy(code, "import ", 7);
            j = 7;
        }
        if (modules[i] == ' ') {
            code[j++] = ',';
            code[j++] = ' ';
        } else {
            code[j++] = modules[i];
        }
    }
    code[j] = '\0';
    /* the probe ends with an exit status of its own: a program that exits 0 whatever it is given
     * (HEXAGLIDE_PYTHON=/bin/true) is no Python that imported them */
    snprintf(code + j, sizeof code - j, "; raise SystemExit(%d)", PY_PROBE_STATUS);
    if (pipe(fd) != 0) {
        snprintf(why, len, "cannot run it (pipe: %s)", strerror(errno));
        return -1;
    }
    pid = fork();
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        if (null >= 0) {
            dup2(null, 0);
            dup2(null, 1);
        }
        dup2(fd[1], 2);
        close(fd[0]);
        close(fd[1]);
        execl(python, python, "-c", code, (char *)0);
        fprintf(stderr, "cannot run it: %s\n", strerror(errno));
        _exit(127);
    }
    close(fd[1]);
    if (pid < 0) {
        close(fd[0]);
        snprintf(why, len, "cannot run it (fork: %s)", strerror(errno));
        return -1;
    }
    while ((got = read(fd[0], buf + used, sizeof buf - 1 - used)) > 0) {
        used += (size_t)got;
        if (used == sizeof buf - 1) {      /* keep the tail */
            memmove(buf, buf + sizeof buf / 2, used - sizeof buf / 2);
            used -= sizeof buf / 2;
        }
    }
    close(fd[0]);
    if (waitpid(pid, &status, 0) < 0)
        status = -1;
    if (WIFEXITED(status) && WEXITSTATUS(status) == PY_PROBE_STATUS)
        return 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        snprintf(why, len, "it is no python3: it exited 0 where Python exits %d (python3 -c '%s')", PY_PROBE_STATUS,
                 code);
        return -1;
    }
    while (used > 0 && (buf[used - 1] == '\n' || buf[used - 1] == ' '))
        used--;
    buf[used] = '\0';
    {
        const char *last = strrchr(buf, '\n');
        const char *msg = used ? (last ? last + 1 : buf)
                               : WIFEXITED(status) ? "exit status without a message" : "killed by a signal";
        size_t ml = strlen(msg) < len ? strlen(msg) : len - 1;   /* cut to fit */
        memcpy(why, msg, ml);
        why[ml] = '\0';
    }
    return -1;
}

int cli_find_python(const char *cmd, const char *modules, const char *why, char *out, size_t len)
{
    static char tried[PY_TRIED_MAX][PATH_MAX], shown[PY_TRIED_MAX][PATH_MAX], reason[PY_TRIED_MAX][256];
    const char *env = getenv("HEXAGLIDE_PYTHON"), *path = getenv("PATH");
    char dir[PATH_MAX], cand[PATH_MAX], real[PATH_MAX], pkgs[256];
    int n = 0, i, k;
    size_t used = 0;
    if (env && *env) {
        char r[256];
        if (python_imports(env, modules, r, sizeof r) == 0 && snprintf(out, len, "%s", env) < (int)len)
            return 0;
        fprintf(stderr, "hexaglide %s: HEXAGLIDE_PYTHON=%s does not import %s: %s\n"
                "hexaglide %s: %s; set HEXAGLIDE_PYTHON to a python3 that has them, or unset it to search "
                "$PATH\n", cmd, env, modules, r, cmd, why);
        return -1;
    }
    while (path && *path && n < PY_TRIED_MAX) {
        const char *start = path, *colon = strchr(path, ':');
        size_t dl = colon ? (size_t)(colon - path) : strlen(path);
        int seen = 0;
        path = colon ? colon + 1 : path + dl;
        if (dl == 0 || dl >= sizeof dir)   /* an empty entry (the cwd) is not searched */
            continue;
        memcpy(dir, start, dl);
        dir[dl] = '\0';
        if (snprintf(cand, sizeof cand, "%s/python3", dir) >= (int)sizeof cand || access(cand, X_OK) != 0 ||
            !realpath(cand, real))
            continue;
        for (i = 0; i < n; i++)        /* /bin/python3 is /usr/bin/python3 */
            seen |= strcmp(tried[i], real) == 0;
        if (seen)
            continue;
        if (python_imports(cand, modules, reason[n], sizeof reason[n]) == 0 &&
            snprintf(out, len, "%s", cand) < (int)len)
            return 0;
        snprintf(tried[n], sizeof tried[n], "%s", real);
        snprintf(shown[n], sizeof shown[n], "%s", cand);
        n++;
    }
    pkgs[0] = '\0';
    for (i = 0, k = 1; modules[i] && used + 16 < sizeof pkgs; i++) {   /* "a b" -> "python3-a python3-b" */
        if (k)
            used += (size_t)snprintf(pkgs + used, sizeof pkgs - used, "%spython3-", used ? " " : "");
        k = modules[i] == ' ';
        if (!k)
            pkgs[used++] = modules[i];
        pkgs[used] = '\0';
    }
    fprintf(stderr, "hexaglide %s: no python3 on $PATH imports %s (%s):\n", cmd, modules, why);
    for (i = 0; i < n; i++)
        fprintf(stderr, "  %s: %s\n", shown[i], reason[i]);
    if (n == 0)
        fprintf(stderr, "  (no python3 on $PATH at all)\n");
    fprintf(stderr, "hexaglide %s: on Debian 12: apt-get install %s (as root; Debian's /usr/bin/python3 "
            "then has them), or set HEXAGLIDE_PYTHON to a python3 that imports them\n", cmd, pkgs);
    return -1;
}

/* Where writing path goes into t: symlinks followed, a dangling one's
 * target too (the link stays a link). 0, or -1 with errno set. */
static int out_target(const char *path, char *t, size_t len)
{
    char link[PATH_MAX], next[PATH_MAX];
    struct stat sb;
    int hops, keep;
    ssize_t n;
    errno = ENAMETOOLONG;
    if (snprintf(t, len, "%s", path) >= (int)len)
        return -1;
    for (hops = 0; lstat(t, &sb) == 0 && S_ISLNK(sb.st_mode); hops++) {
        const char *slash = strrchr(t, '/');
        if (hops == 40) {
            errno = ELOOP;
            return -1;
        }
        if ((n = readlink(t, link, sizeof link - 1)) < 0)
            return -1;
        link[n] = '\0';
        keep = link[0] != '/' && slash ? (int)(slash - t + 1) : 0;   /* a relative link: t's directory */
        errno = ENAMETOOLONG;
        if (snprintf(next, sizeof next, "%.*s%s", keep, t, link) >= (int)sizeof next ||
            snprintf(t, len, "%s", next) >= (int)len)
            return -1;
    }
    return 0;
}

/* The directory part of path ("." for none) into d. */
static void dir_of(const char *path, char *d, size_t len)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(d, len, ".");
    else
        snprintf(d, len, "%.*s", slash == path ? 1 : (int)(slash - path), path);
}

/* The file name of path (after its last '/'). */
static const char *base_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

int cli_out_is_stdout(const char *path)
{
    return !path || strcmp(path, "-") == 0;
}

int cli_out_need_file(const char *cmd, const char *opt, const char *path, const char *why)
{
    if (!path || strcmp(path, "-") != 0)
        return 0;
    fprintf(stderr, "hexaglide %s: %s -: '-' is standard output, which %s cannot take (%s); give a file "
            "(./- for one named '-')\n", cmd, opt, opt, why);
    return -1;
}

int cli_out_need_regular(const char *cmd, const char *opt, const char *path, const char *why)
{
    char t[PATH_MAX], d[PATH_MAX], probe[PATH_MAX + 32];
    struct stat sb;
    int fd;
    if (cli_out_is_stdout(path))
        return 0;
    if (out_target(path, t, sizeof t)) {
        fprintf(stderr, "hexaglide %s: cannot write %s %s: %s\n", cmd, opt, path, strerror(errno));
        return -1;
    }
    if (stat(t, &sb) == 0 && !S_ISREG(sb.st_mode)) {
        fprintf(stderr, "hexaglide %s: %s %s: it is %s, and %s; give a file\n", cmd, opt, path,
                S_ISDIR(sb.st_mode) ? "a directory" : "no regular file (a device or FIFO)", why);
        return -1;
    }
    dir_of(t, d, sizeof d);
    snprintf(probe, sizeof probe, "%s/.hexaglide-probe-%ld", d, (long)getpid());
    fd = open(probe, O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0) {
        int err = errno;
        if (err == ENOENT && access(d, F_OK) != 0)
            fprintf(stderr, "hexaglide %s: cannot write %s %s: no directory %s\n", cmd, opt, path, d);
        else
            fprintf(stderr, "hexaglide %s: cannot write %s %s: %s (a new file in %s)\n", cmd, opt, path,
                    strerror(err), d);
        return -1;
    }
    close(fd);
    unlink(probe);
    return 0;
}

int cli_out_is_input(const char *cmd, const char *opt, const char *out, const char *in_opt, const char *in)
{
    if (cli_out_is_stdout(out) || !in || !cli_out_same(out, in))
        return 0;
    fprintf(stderr, "hexaglide %s: %s %s names the file the command reads (%s%s%s): it would be overwritten; "
            "give another file\n", cmd, opt, out, in_opt, in_opt[0] ? " " : "", in);
    return 1;
}

int cli_out_same(const char *a, const char *b)
{
    char ta[PATH_MAX], tb[PATH_MAX], da[PATH_MAX], db[PATH_MAX];
    struct stat sa, sb;
    int ea, eb;
    if (cli_out_is_stdout(a) || cli_out_is_stdout(b))
        return cli_out_is_stdout(a) && cli_out_is_stdout(b);
    if (out_target(a, ta, sizeof ta) || out_target(b, tb, sizeof tb))
        return 0;                      /* (opening it says why) */
    ea = stat(ta, &sa) == 0;
    eb = stat(tb, &sb) == 0;
    if (ea || eb)
        return ea && eb && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    dir_of(ta, da, sizeof da);         /* neither exists yet: the same name in the same directory */
    dir_of(tb, db, sizeof db);
    return strcmp(base_of(ta), base_of(tb)) == 0 && stat(da, &sa) == 0 && stat(db, &sb) == 0 &&
           sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

int cli_out_open(const char *cmd, const char *path, cli_out *o)
{
    struct stat sb;
    int fd, direct, exists;
    o->path = cli_out_is_stdout(path) ? 0 : path;
    o->tmp[0] = '\0';
    o->f = stdout;
    if (!o->path)
        return 0;
    if (out_target(path, o->target, sizeof o->target)) {
        fprintf(stderr, "hexaglide %s: cannot write %s: %s\n", cmd, path, strerror(errno));
        return -1;
    }
    exists = stat(o->target, &sb) == 0;
    direct = exists && !S_ISREG(sb.st_mode);
    if (direct && S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "hexaglide %s: cannot write %s: it is a directory; give a file\n", cmd, path);
        return -1;
    }
    if (direct) {                      /* a FIFO, a device: straight into it */
        signal(SIGPIPE, SIG_IGN);      /* a reader that leaves is a write error, with a message */
        fd = open(o->target, O_WRONLY | O_NOCTTY);
    } else {                           /* a temporary beside the target, renamed onto it */
        if (snprintf(o->tmp, sizeof o->tmp, "%s.tmp-%ld", o->target, (long)getpid()) >= (int)sizeof o->tmp) {
            fprintf(stderr, "hexaglide %s: cannot write %s: path too long\n", cmd, path);
            return -1;
        }
        fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0 && exists && fchmod(fd, sb.st_mode & 07777) != 0) {   /* a file replaced keeps its mode */
            close(fd);
            fd = -1;
        }
    }
    if (fd < 0 || !(o->f = fdopen(fd, "w"))) {
        char d[PATH_MAX];
        int err = errno;
        dir_of(o->target, d, sizeof d);
        if (err == ENOENT && !direct && access(d, F_OK) != 0)
            fprintf(stderr, "hexaglide %s: cannot write %s: no directory %s\n", cmd, path, d);
        else
            fprintf(stderr, "hexaglide %s: cannot write %s: %s\n", cmd, path, strerror(err));
        if (fd >= 0) {
            close(fd);
            if (!direct)
                unlink(o->tmp);
        }
        return -1;
    }
    return 0;
}

static int stdout_errno;               /* the first failed write's cause (0: none) */

/* stdout's writer: all n bytes to fd 1, or -1 keeping the cause (stdio forgets it once
 * a large fputs bypassed the buffer). */
static ssize_t stdout_write(void *cookie, const char *buf, size_t n)
{
    size_t done = 0;
    (void)cookie;
    while (done < n) {
        ssize_t w = write(STDOUT_FILENO, buf + done, n - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            if (!stdout_errno)
                stdout_errno = w < 0 ? errno : EIO;
            return -1;
        }
        done += (size_t)w;
    }
    return (ssize_t)n;
}

void cli_stdout_init(void)
{
    cookie_io_functions_t io = {0, stdout_write, 0, 0};
    FILE *f = fopencookie(0, "w", io);
    if (!f)
        return;                        /* stdio's own stdout then: the cause may read EIO */
    if (isatty(STDOUT_FILENO))
        setvbuf(f, 0, _IOLBF, BUFSIZ); /* a terminal sees each line as before */
    stdout = f;
}

int cli_stdout_flush(const char *cmd)
{
    static int reported;               /* once: sim's CSV to stdout, then main */
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout))
        return 0;
    if (!reported)
        fprintf(stderr, "hexaglide %s: writing stdout failed: %s; the output is incomplete\n", cmd,
                strerror(stdout_errno ? stdout_errno : errno ? errno : EIO));
    reported = 1;
    return -1;
}

int cli_out_close(const char *cmd, cli_out *o, int keep)
{
    int err = 0, renamed = o->path && o->tmp[0];
    errno = 0;
    if (!o->path)
        return cli_stdout_flush(cmd);
    if (fflush(o->f) != 0 || ferror(o->f))
        err = errno ? errno : EIO;
    if (!err && renamed && keep && fsync(fileno(o->f)) != 0)
        err = errno;
    if (fclose(o->f) != 0 && !err)
        err = errno;
    if (!err && renamed && keep && rename(o->tmp, o->target) != 0)
        err = errno;
    if (renamed && (err || !keep))
        unlink(o->tmp);
    if (err)
        fprintf(stderr, "hexaglide %s: writing %s failed: %s%s\n", cmd, o->path, strerror(err),
                renamed ? " (nothing written)" : "");
    return err ? -1 : 0;
}

int cli_read_file(const char *cmd, const char *path, const char *what, long long max, char **buf, size_t *len)
{
    FILE *f = fopen(path, "rb");
    struct stat sb;
    long long size;
    size_t got;
    if (!f) {
        fprintf(stderr, "hexaglide %s: %s: %s\n", cmd, path, strerror(errno));
        return -1;
    }
    if (fstat(fileno(f), &sb) != 0 || !S_ISREG(sb.st_mode) || fseek(f, 0, SEEK_END) != 0 ||
        (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "hexaglide %s: %s: not a regular file (cannot seek); give %s\n", cmd, path, what);
        fclose(f);
        return -1;
    }
    if (size > max) {
        fprintf(stderr, "hexaglide %s: %s: %lld bytes, more than the %lld this reads; give %s\n", cmd, path, size,
                max, what);
        fclose(f);
        return -1;
    }
    *buf = malloc((size_t)size + 1);
    if (!*buf) {
        fprintf(stderr, "hexaglide %s: %s: out of memory for %lld bytes\n", cmd, path, size);
        fclose(f);
        return -1;
    }
    got = fread(*buf, 1, (size_t)size, f);
    fclose(f);
    if (got != (size_t)size) {
        fprintf(stderr, "hexaglide %s: %s: read %zu of %lld bytes\n", cmd, path, got, size);
        free(*buf);
        return -1;
    }
    (*buf)[got] = '\0';
    *len = got;
    return 0;
}
