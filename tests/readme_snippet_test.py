#!/usr/bin/env python3
"""The README's C++ example compiles against the core's headers as printed: its ```cpp block is
wrapped in a function whose parameters are the names it leaves to the reader (the engine's
matrices and the scene box), and given to the compiler with -fsyntax-only.

  readme_snippet_test.py README.md CXX INCLUDE_DIR...
"""
import os
import re
import subprocess
import sys
import tempfile

readme, compiler, includes = sys.argv[1], sys.argv[2], sys.argv[3:]
blocks = re.findall(r"```cpp\n(.*?)```", open(readme, encoding="utf-8").read(), re.S)
if not blocks:
    sys.exit(f"FAIL: {readme}: no ```cpp block")
source = """#include "shadowkit/core/engine_camera.h"
#include "shadowkit/core/output_conventions.h"
#include "shadowkit/core/shadow_setup.h"

void readmeExample(const glm::dmat4& viewFromWorld, const glm::dmat4& clipFromView, const glm::dvec3& worldMin,
                   const glm::dvec3& worldMax) {
""" + blocks[0] + "}\n"
with tempfile.NamedTemporaryFile("w", suffix=".cpp", delete=False) as f:
    f.write(source)
result = subprocess.run([compiler, "-std=c++20", "-fsyntax-only", "-Wall", "-Wno-unused-variable",
                         *[f"-I{i}" for i in includes], f.name], capture_output=True, text=True)
os.unlink(f.name)
if result.returncode != 0:
    sys.exit(f"FAIL: the README's C++ example does not compile:\n{result.stderr}")
print("the README's C++ example compiles against the core's headers")
