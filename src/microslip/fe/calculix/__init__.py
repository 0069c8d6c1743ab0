"""CalculiX (``ccx``) on the clamped bar: deck, run and read-back.

- :mod:`~microslip.fe.calculix.mesh`: structured C3D20 mesh of the bar on a rigid C3D8 base;
- :mod:`~microslip.fe.calculix.case`: the validated load case (:class:`FECase`);
- :mod:`~microslip.fe.calculix.deck`: the ``.inp`` deck, one tested function per keyword card;
- :mod:`~microslip.fe.calculix.runner`: ``ccx`` with a time-out and typed failures;
- :mod:`~microslip.fe.calculix.readers`: ``.dat``, ``.sta`` and ``.frd`` readers;
- :mod:`~microslip.fe.calculix.collect`: a CalculiX run read into an
  :class:`~microslip.fe.result.FELoopResult`;
- :mod:`~microslip.fe.calculix.meshdeck`: the deck of the user's own
  :class:`~microslip.fe.hexmesh.HexMesh` with named sets and
  :class:`~microslip.fe.meshload.MeshLoad` loads (issue 22), and
  :mod:`~microslip.fe.calculix.meshhistory` its load history;
- :mod:`~microslip.fe.calculix.meshrun`: that deck run and read into a
  :class:`~microslip.fe.calculix.meshrun.MeshCalculixResult`;
- :mod:`~microslip.fe.calculix.contactform`: the deck's contact formulations (face-to-face,
  node-to-surface);
- :mod:`~microslip.fe.calculix.compare`: the built-in solver against CalculiX on the same
  mesh, like with like (``validate --mesh``, issue 29).
"""
