"""The solvers' numeric tolerances: rendered into every generated module and listed in every audit report (the
report template says why each holds)."""

TOLERANCES = {"singular": "1e-6", "gimbal": "1e-10", "tangent": "1e-12", "fk_residual": "1e-10",
              "fk_duplicate": "1e-7", "fk_fold": "1e-8", "touch": "1e-8", "degenerate": "1e-12",
              "on_axis": "1.4210854715202004e-14",  # 64 eps
              "ik_verify": "1e-9", "rotation": "1e-9", "stage_tangent": "1e-9", "stage_tangent_max": "1e-6",
              "stage_noise": "3.552713678800501e-15",  # 16 eps
              "double_root": "1e-12",
              "double_root_polish": "1e-12",
              "root_gap": "5.684341886080802e-14",  # 256 eps
              "wrist_exact": "1e-13",
              "wrist_family": "1.4210854715202004e-14",  # 64 eps
              "design_scale_min": "1e-3", "length_min": "1e-5", "length_max": "1e6"}
