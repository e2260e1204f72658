"""Running work: the one layer that knows about processes.

A command makes an executor where it starts (:func:`spare_core` for a one-off command,
:class:`Pool` for independent jobs, :data:`SERIAL` for none) and hands it to the code that has
work to share, which submits tasks and reads their results without knowing where they ran. The
study runner and the design search run their cases and trials on a :class:`Supervisor` (a
local pool or a Dask cluster, what is done when a worker dies, SIGTERM and SIGINT); a class's
samples run on a :class:`Cluster` where one is given; a benchmark's run takes a process of its
own (:func:`in_fresh_process`). A one-off command's executor can hold processes made ready
at its start (:class:`Primed`: matplotlib imported while the command starts up) for the
pictures it draws after its solve.

>>> from fegear.running import SERIAL, Forks
>>> task = SERIAL.submit(pow, 2, 10)     # serial: run when its result is read
>>> task.done(), task.result(), task.done()
(False, 1024, True)
>>> with Forks(2) as forks:              # a forked copy of this process in parallel
...     forks.map(abs, [-1, -2, -3])
[1, 2, 3]
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "executors": ("Executor", "Task", "Serial", "SERIAL", "Forks", "Pool", "Cluster",
                  "spare_core",
                  "pool_or_serial", "in_fresh_process"),
    "forks": ("WorkerFailed", "strict", "STRICT"),
    "primed": ("Primed",),
    "pools": ("LocalPool", "init_worker", "connect"),
    "supervisor": ("Supervisor", "Outcome"),
})
