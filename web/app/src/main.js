// The pkm serve web application (docs/web.md): one page, four views, on the JSON API only.
import "./style.css";

const $ = (s) => document.querySelector(s);
for (const b of document.querySelectorAll("#views button"))
  b.addEventListener("click", () => {
    for (const o of document.querySelectorAll("#views button")) o.classList.toggle("active", o === b);
    for (const v of document.querySelectorAll(".view"))
      v.classList.toggle("active", v.id === "view-" + b.dataset.view);
  });
$("#status").textContent = "";
