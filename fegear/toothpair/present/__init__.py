"""The tooth-pair stage's presentation: what a designer reads of a solve, from its summary and
solutions, never solving anything. The tables ``fegear solve`` prints (:mod:`.tables`), the
report page (:mod:`.html_report`, its shared parts :mod:`.html_parts`), what the pictures
mark (:mod:`.marks`), the pictures (:mod:`.plot`; :mod:`.pictured`: a solved pair made ready
to draw in another process), a solved job's files (:mod:`.output`: :func:`~.output.write_job`,
:func:`~.output.run_job`) and the writers the analyses share (:mod:`.writers`).

It reads the core (:mod:`fegear.toothpair`'s solve) and reaches the analyses only through
their registry (:mod:`fegear.toothpair.analyses`: which are shown, their verdicts, what a
writer is handed); an analysis's own tables, files and pictures are in its folder.
"""
