file(WRITE ${WORK_DIR}/placeholder "")
