"""What the study scripts of docs/studies/ say about the machine they ran on."""
import platform


def host_processor():
    """The CPU's model name (two hosts of one machine kind can differ by 20 %: name it)."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"
