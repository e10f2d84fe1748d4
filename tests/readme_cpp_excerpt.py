"""The README's C++ lines are examples/cpp/main.cpp's (the README shows its
heart, the test builds the whole): each code line of the README's ```cpp
block, without its trailing // comment, is a line of main.cpp."""
import re
import sys

readme, source = open(sys.argv[1]).read(), open(sys.argv[2]).read()
blocks = re.findall(r"```cpp\n(.*?)```", readme, re.S)
if len(blocks) != 1:
    sys.exit("README.md should hold one C++ example")
lines = {line.strip() for line in source.splitlines()}
for line in blocks[0].splitlines():
    code = line.split("//")[0].strip()
    if code and code not in lines:
        sys.exit(f"README.md shows a C++ line that examples/cpp/main.cpp does not have: {code}")
