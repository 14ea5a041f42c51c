"""The generated C from other build systems and languages: a C++ program links every mechanism (the headers'
extern "C" guards), and a CMake project adds the solvers with add_subdirectory (generated/c/CMakeLists.txt)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
import wristkin
from cbuild import STRICT_FLAGS, compiler

ROOT = Path(__file__).resolve().parent.parent
C_DIR = ROOT / "generated" / "c"

CPP_MAIN = """
#include <cmath>
#include <cstdio>
{includes}

int main()
{{
    const double q[6] = {{0.1, -0.4, 0.3, 0.2, 0.5, -0.1}};
    wk_puma560_fk_solutions fk;
    wk_puma560_ik_solutions ik;
    wk_underactuated_wrist_ik_solutions uik;
    const double uw_pose[3] = {{-0.628, 0.0045, 0.679}};
    if (wk_puma560_fk(q, nullptr, &fk) != WK_OK || fk.count != 1) return 1;
    if (wk_puma560_ik(fk.values[0], nullptr, &ik) != WK_OK || ik.count != 8) return 2;
    if (wk_underactuated_wrist_ik(uw_pose, nullptr, &uik) != WK_OK || uik.count < 1) return 3;
    if (wk_puma560_fk(nullptr, nullptr, &fk) != WK_ERR_NULL) return 4;
    std::printf("%s %d %d\\n", wk_strerror(WK_ERR_NONFINITE), ik.count, uik.count);
    return 0;
}}
"""


def cpp_source() -> str:
    includes = "\n".join(f'#include "{n}.h"' for n in wristkin.MECHANISMS)
    return CPP_MAIN.format(includes=includes)


def test_a_cpp_program_links_every_mechanism(tmp_path):
    cxx = shutil.which("g++") or shutil.which("c++")
    if cxx is None:
        pytest.skip("no C++ compiler on this machine")
    objects = []
    for name in (*wristkin.MECHANISMS, "wristkin_runtime"):
        obj = tmp_path / f"{name}.o"
        subprocess.run([compiler(), *STRICT_FLAGS, f"-I{C_DIR}", "-c", str(C_DIR / f"{name}.c"), "-o", str(obj)],
                       check=True, capture_output=True, text=True)
        objects.append(str(obj))
    main = tmp_path / "main.cpp"
    main.write_text(cpp_source())
    exe = tmp_path / "app"
    build = subprocess.run([cxx, "-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic", f"-I{C_DIR}", str(main),
                            *objects, "-lm", "-o", str(exe)], capture_output=True, text=True)
    assert build.returncode == 0, build.stderr  # unguarded headers fail here: undefined reference to `wk_...'
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.startswith("input is not finite"), (run.returncode, run.stdout)


def test_cmake_adds_the_solvers_with_one_line(tmp_path):
    cmake = shutil.which("cmake")
    if cmake is None or (shutil.which("g++") or shutil.which("c++")) is None:
        pytest.skip("cmake and a C++ compiler are needed")
    (tmp_path / "main.cpp").write_text(cpp_source())
    (tmp_path / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.13)\nproject(consumer LANGUAGES C CXX)\n"
        f"add_subdirectory({C_DIR.as_posix()} wristkin)\n"
        "add_executable(app main.cpp)\ntarget_link_libraries(app PRIVATE wristkin::solvers)\n")
    build = tmp_path / "build"
    for cmd in ([cmake, "-S", str(tmp_path), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"],
                [cmake, "--build", str(build), "-j", "2"]):
        step = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        assert step.returncode == 0, step.stdout + step.stderr
    run = subprocess.run([str(build / "app")], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.startswith("input is not finite"), (run.returncode, run.stdout)
